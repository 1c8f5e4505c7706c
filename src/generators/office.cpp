// A parametric office building, the kind of densely occluded model of the paper's Fig. 1 and §7.
#include "generators/office.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "generators/scene_builder.h"
#include "generators/seeded_random.h"

namespace gv {
namespace {

// Clearances (metres). Furniture keeps this far from walls so that its faces never touch a wall's.
constexpr double kFurnitureWallGap = 0.05;
// The strip along the door wall kept free of furniture, so that doors stay usable and the
// "through the door" sight lines of the tests exist.
constexpr double kDoorClearance = 1.2;
// Doors keep this far from the room's corners (room for the jamb and a light switch).
constexpr double kDoorCornerMargin = 0.3;
// Light panels hang this far below the ceiling: not coplanar with it, so no overlapping patches.
constexpr double kLightDrop = 0.02;
constexpr double kRoomLightWidth = 1.2, kRoomLightDepth = 0.6;
constexpr double kCorridorLightSize = 0.6;

struct Materials {
  uint32_t wall, floor, ceiling, jamb, exterior, desk, cabinet, light;
};

Materials addMaterials(Scene& scene, double emission) {
  Materials m{};
  m.wall = scene.addMaterial({"wall", {0.75, 0.73, 0.68}, {}});
  m.floor = scene.addMaterial({"floor", {0.45, 0.40, 0.35}, {}});
  m.ceiling = scene.addMaterial({"ceiling", {0.80, 0.80, 0.78}, {}});
  m.jamb = scene.addMaterial({"jamb", {0.35, 0.45, 0.70}, {}});
  m.exterior = scene.addMaterial({"exterior", {0.55, 0.55, 0.55}, {}});
  m.desk = scene.addMaterial({"desk", {0.60, 0.45, 0.30}, {}});
  m.cabinet = scene.addMaterial({"cabinet", {0.50, 0.55, 0.60}, {}});
  m.light = scene.addMaterial({"light", {0.8, 0.8, 0.8}, {emission, emission, emission}});
  return m;
}

void validate(const OfficeOptions& o) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("office options: ") + what);
  };
  require(o.floors >= 1 && o.rows >= 1 && o.columns >= 1, "floors, rows, columns must be >= 1");
  require(o.roomWidth > 0 && o.roomDepth > 0 && o.corridorWidth > 0 && o.storeyHeight > 0 &&
              o.slabThickness > 0 && o.wallThickness > 0,
          "sizes must be positive");
  require(!o.doors || (o.doorWidth > 0 && o.doorHeight > 0 && o.doorHeight < o.storeyHeight &&
                       o.doorWidth + 2 * kDoorCornerMargin <= o.roomWidth),
          "door does not fit its wall (needs 0.3 m beside it)");
  require(!o.windows || (o.windowWidth > 0 && o.windowWidth < o.roomDepth && o.windowSill > 0 &&
                         o.windowSill < o.windowHead && o.windowHead < o.storeyHeight),
          "window does not fit its wall");
  require(o.furniturePerRoom >= 0, "furniturePerRoom must be >= 0");
  require(!o.furniture || o.furniturePerRoom == 0 ||
              (o.roomDepth > kDoorClearance + 0.5 &&
               (o.roomWidth - 2 * kFurnitureWallGap) / o.furniturePerRoom >= 0.3),
          "rooms too small for their furniture");
  require(!o.lights || (o.lightEmission >= 0 && o.roomWidth > kRoomLightWidth &&
                        o.roomDepth > kRoomLightDepth && o.corridorWidth > kCorridorLightSize &&
                        o.storeyHeight > kLightDrop),
          "light panels do not fit");
}

// The layout of the header comment, as functions.
struct Layout {
  const OfficeOptions& o;
  double t, pitchY, storeyPitch;
  explicit Layout(const OfficeOptions& opts)
      : o(opts),
        t(opts.wallThickness),
        pitchY(opts.corridorWidth + 2 * opts.wallThickness + opts.roomDepth),
        storeyPitch(opts.storeyHeight + opts.slabThickness) {}
  double sizeX() const { return t + o.columns * (o.roomWidth + t); }
  double sizeY() const { return t + o.rows * pitchY; }
  double sizeZ() const { return o.floors * storeyPitch + o.slabThickness; }
  double roomX0(int c) const { return t + c * (o.roomWidth + t); }
  double rowY0(int r) const { return t + r * pitchY; }  ///< the corridor's -y side
  double roomY0(int r) const { return rowY0(r) + o.corridorWidth + t; }
  double floorZ(int f) const { return f * storeyPitch + o.slabThickness; }  ///< top of slab f
  double ceilingZ(int f) const { return (f + 1) * storeyPitch; }
};

size_t boxesPerStorey(const OfficeOptions& o) {
  const size_t rows = static_cast<size_t>(o.rows), columns = static_cast<size_t>(o.columns);
  const size_t corridorWall = o.doors ? 2 * columns + 1 : 1;
  const size_t partition = o.windows ? 4 : 1;
  const size_t furniture = o.furniture ? static_cast<size_t>(o.furniturePerRoom) : 0;
  return 4 + rows * (corridorWall + (columns - 1) * (partition + furniture) + furniture) +
         (rows - 1);
}

// A wall along x (constant y range [y0, y1]) from x0 to x1 between z0 and z1, pierced by
// openings [a_i, b_i] x [z0, zTop] (sorted along x): the pieces beside the openings reach full
// height, a lintel spans each opening above zTop. Jambs and heads get the jamb material.
void addWallAlongX(SceneBuilder& builder, double x0, double x1, double y0, double y1, double z0,
                   double z1, const std::vector<std::pair<double, double>>& openings,
                   double zTop, const Materials& m) {
  double start = x0;
  BoxMaterials pieceMaterials = BoxMaterials::uniform(m.wall);
  for (const auto& [a, b] : openings) {
    BoxMaterials piece = pieceMaterials;
    piece.face[1] = m.jamb;  // +x face: the opening's left jamb
    builder.addBox({start, y0, z0}, {a, y1, z1}, piece);
    BoxMaterials lintel = BoxMaterials::uniform(m.wall);
    lintel.face[4] = m.jamb;  // -z face: the head of the opening
    builder.addBox({a, y0, zTop}, {b, y1, z1}, lintel);
    pieceMaterials = BoxMaterials::uniform(m.wall);
    pieceMaterials.face[0] = m.jamb;  // -x face of the next piece: the right jamb
    start = b;
  }
  builder.addBox({start, y0, z0}, {x1, y1, z1}, pieceMaterials);
}

// The furniture of one room: the usable floor (clear of walls and the door zone) is cut into
// `count` strips along x, one piece per strip, so pieces never overlap and placement always
// succeeds (the patch count is exact).
void addFurniture(SceneBuilder& builder, SeededRandom& random, const OfficeOptions& o,
                  double x0, double y0, double z, const Materials& m) {
  const double ux0 = x0 + kFurnitureWallGap, ux1 = x0 + o.roomWidth - kFurnitureWallGap;
  const double uy0 = y0 + kDoorClearance, uy1 = y0 + o.roomDepth - kFurnitureWallGap;
  const double strip = (ux1 - ux0) / o.furniturePerRoom;
  for (int k = 0; k < o.furniturePerRoom; ++k) {
    const bool desk = k % 2 == 0;
    // Desk: 1.2-1.6 x 0.6-0.8 x 0.72-0.76 m; cabinet: 0.4-0.8 x 0.4-0.6 x 1.0-2.0 m.
    double w = desk ? random.uniform(1.2, 1.6) : random.uniform(0.4, 0.8);
    double d = desk ? random.uniform(0.6, 0.8) : random.uniform(0.4, 0.6);
    const double h = desk ? random.uniform(0.72, 0.76) : random.uniform(1.0, 2.0);
    w = std::min(w, 0.9 * strip);
    d = std::min(d, 0.9 * (uy1 - uy0));
    const double sx = ux0 + k * strip;
    const double px = random.uniform(sx, sx + strip - w);
    const double py = random.uniform(uy0, uy1 - d);
    builder.addBox({px, py, z}, {px + w, py + d, z + h}, desk ? m.desk : m.cabinet);
  }
}

// A light panel: the rectangle centred at (cx, cy), facing down at height z.
void addLight(SceneBuilder& builder, double cx, double cy, double sx, double sy, double z,
              uint32_t material) {
  builder.addAxisRect(2, false, {cx - sx / 2, cy - sy / 2, z}, {cx + sx / 2, cy + sy / 2, z},
                      material);
}

}  // namespace

size_t officePatchCount(const OfficeOptions& o) {
  const size_t floors = static_cast<size_t>(o.floors);
  const size_t rooms = static_cast<size_t>(o.rows) * static_cast<size_t>(o.columns);
  return 6 * (floors + 1) + floors * (6 * boxesPerStorey(o) + (o.lights ? 2 * rooms : 0));
}

Scene generateOffice(const OfficeOptions& o) {
  validate(o);
  const Layout L(o);
  const double t = L.t;
  Scene scene;
  const Materials m = addMaterials(scene, o.lightEmission);
  scene.patches.reserve(officePatchCount(o));
  Aabb extent;
  extent.add(Vec3{0, 0, 0});
  extent.add(Vec3{L.sizeX(), L.sizeY(), L.sizeZ()});
  SceneBuilder builder(scene, Tolerance::forBounds(extent));
  SeededRandom random(o.seed);
  const double X = L.sizeX(), Y = L.sizeY();

  // Slabs: top face is a floor, bottom face a ceiling, except the building's bottom and roof.
  for (int f = 0; f <= o.floors; ++f) {
    BoxMaterials slab = BoxMaterials::uniform(m.exterior);
    if (f > 0) slab.face[4] = m.ceiling;
    if (f < o.floors) slab.face[5] = m.floor;
    const double z0 = f * L.storeyPitch;
    builder.addBox({0, 0, z0}, {X, Y, z0 + o.slabThickness}, slab);
  }

  std::vector<std::pair<double, double>> doors;
  for (int f = 0; f < o.floors; ++f) {
    const double z0 = L.floorZ(f), z1 = L.ceilingZ(f);
    // Exterior walls: the +-y walls run the full length, the +-x walls fit between them.
    BoxMaterials outer = BoxMaterials::uniform(m.wall);
    outer.face[2] = m.exterior;
    builder.addBox({0, 0, z0}, {X, t, z1}, outer);
    outer = BoxMaterials::uniform(m.wall);
    outer.face[3] = m.exterior;
    builder.addBox({0, Y - t, z0}, {X, Y, z1}, outer);
    outer = BoxMaterials::uniform(m.wall);
    outer.face[0] = m.exterior;
    builder.addBox({0, t, z0}, {t, Y - t, z1}, outer);
    outer = BoxMaterials::uniform(m.wall);
    outer.face[1] = m.exterior;
    builder.addBox({X - t, t, z0}, {X, Y - t, z1}, outer);

    for (int r = 0; r < o.rows; ++r) {
      const double corridorY0 = L.rowY0(r), roomY0 = L.roomY0(r);
      const double roomY1 = roomY0 + o.roomDepth;
      // The corridor wall, with one door per room at a seeded position.
      doors.clear();
      if (o.doors) {
        for (int c = 0; c < o.columns; ++c) {
          const double a = L.roomX0(c) + random.uniform(kDoorCornerMargin, o.roomWidth -
                                                                                kDoorCornerMargin -
                                                                                o.doorWidth);
          doors.emplace_back(a, a + o.doorWidth);
        }
      }
      addWallAlongX(builder, t, X - t, roomY0 - t, roomY0, z0, z1, doors, z0 + o.doorHeight, m);
      // The back wall (the last row's is the exterior wall).
      if (r + 1 < o.rows) builder.addBox({t, roomY1, z0}, {X - t, roomY1 + t, z1}, m.wall);
      // Partitions between neighbouring rooms, with a window.
      for (int c = 0; c + 1 < o.columns; ++c) {
        const double x0 = L.roomX0(c) + o.roomWidth, x1 = x0 + t;
        if (!o.windows) {
          builder.addBox({x0, roomY0, z0}, {x1, roomY1, z1}, m.wall);
          continue;
        }
        const double w0 = roomY0 + 0.5 * (o.roomDepth - o.windowWidth), w1 = w0 + o.windowWidth;
        BoxMaterials side = BoxMaterials::uniform(m.wall);
        side.face[3] = m.jamb;
        builder.addBox({x0, roomY0, z0}, {x1, w0, z1}, side);
        side = BoxMaterials::uniform(m.wall);
        side.face[2] = m.jamb;
        builder.addBox({x0, w1, z0}, {x1, roomY1, z1}, side);
        BoxMaterials sill = BoxMaterials::uniform(m.wall);
        sill.face[5] = m.jamb;
        builder.addBox({x0, w0, z0}, {x1, w1, z0 + o.windowSill}, sill);
        BoxMaterials head = BoxMaterials::uniform(m.wall);
        head.face[4] = m.jamb;
        builder.addBox({x0, w0, z0 + o.windowHead}, {x1, w1, z1}, head);
      }
      for (int c = 0; c < o.columns; ++c) {
        const double roomX0 = L.roomX0(c);
        if (o.furniture && o.furniturePerRoom > 0) {
          addFurniture(builder, random, o, roomX0, roomY0, z0, m);
        }
        if (o.lights) {
          const double cx = roomX0 + 0.5 * o.roomWidth;
          addLight(builder, cx, roomY0 + 0.5 * o.roomDepth, kRoomLightWidth, kRoomLightDepth,
                   z1 - kLightDrop, m.light);
          addLight(builder, cx, corridorY0 + 0.5 * o.corridorWidth, kCorridorLightSize,
                   kCorridorLightSize, z1 - kLightDrop, m.light);
        }
      }
    }
  }
  return scene;
}

OfficeOptions officeOptionsForPatchCount(size_t target) {
  OfficeOptions o;
  const double perDefault = static_cast<double>(officePatchCount(o));
  o.floors = std::max(1, static_cast<int>(std::lround(std::cbrt(static_cast<double>(target) /
                                                                perDefault))));
  // Rooms per storey, at the default's ~45 patches per room, as rows x (2 rows) columns.
  const double perRoom = perDefault / (o.rows * o.columns);
  const double rooms = std::max(1.0, static_cast<double>(target) / o.floors / perRoom);
  o.rows = std::max(1, static_cast<int>(std::lround(std::sqrt(rooms / 2))));
  // The count is affine in columns: solve for the best one.
  o.columns = 1;
  const double c1 = static_cast<double>(officePatchCount(o));
  o.columns = 2;
  const double slope = static_cast<double>(officePatchCount(o)) - c1;
  o.columns = std::max(1, 1 + static_cast<int>(std::lround((static_cast<double>(target) - c1) /
                                                            slope)));
  return o;
}

Aabb officeRoomInterior(const OfficeOptions& o, int floor, int row, int column) {
  const Layout L(o);
  Aabb box;
  box.add(Vec3{L.roomX0(column), L.roomY0(row), L.floorZ(floor)});
  box.add(Vec3{L.roomX0(column) + o.roomWidth, L.roomY0(row) + o.roomDepth, L.ceilingZ(floor)});
  return box;
}

Aabb officeCorridorInterior(const OfficeOptions& o, int floor, int row) {
  const Layout L(o);
  Aabb box;
  box.add(Vec3{L.t, L.rowY0(row), L.floorZ(floor)});
  box.add(Vec3{L.sizeX() - L.t, L.rowY0(row) + o.corridorWidth, L.ceilingZ(floor)});
  return box;
}

}  // namespace gv
