// A furnished room after the test room of hierarchical radiosity (HSA91, SPLASH-2 RADIOSITY).
#include "generators/furnished_room.h"

#include <stdexcept>

#include "generators/scene_builder.h"

namespace gv {
namespace {

constexpr double kLightDrop = 0.02;  ///< panels hang below the ceiling, not coplanar with it
constexpr double kLightSize = 0.8;
constexpr double kLegSide = 0.06;

/// A table or a chair seat: a top slab on four legs set in from its corners by `inset`.
void addTopOnLegs(SceneBuilder& b, const Vec3& lo, const Vec3& hi, double inset,
                  uint32_t material) {
  b.addBox(lo, hi, material);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const double x = i == 0 ? lo.x + inset : hi.x - inset - kLegSide;
      const double y = j == 0 ? lo.y + inset : hi.y - inset - kLegSide;
      b.addBox({x, y, 0}, {x + kLegSide, y + kLegSide, lo.z}, material);
    }
}

/// A chair centred at (cx, cy) whose backrest stands on the seat's edge facing away from the
/// table: `backAxis` 0 = along x (the back at the -x or +x edge), 1 = along y; `backSign` says
/// which edge.
void addChair(SceneBuilder& b, double cx, double cy, int backAxis, int backSign,
              uint32_t material) {
  constexpr double half = 0.225, seatLow = 0.43, seatHigh = 0.47, backHeight = 0.45,
                   backThickness = 0.04;
  const Vec3 lo{cx - half, cy - half, seatLow}, hi{cx + half, cy + half, seatHigh};
  addTopOnLegs(b, lo, hi, 0.02, material);
  Vec3 backLo{lo.x, lo.y, seatHigh}, backHi{hi.x, hi.y, seatHigh + backHeight};
  if (backAxis == 0) {
    if (backSign > 0)
      backLo.x = hi.x - backThickness;
    else
      backHi.x = lo.x + backThickness;
  } else {
    if (backSign > 0)
      backLo.y = hi.y - backThickness;
    else
      backHi.y = lo.y + backThickness;
  }
  b.addBox(backLo, backHi, material);
}

/// Two sides, a top, a bottom and three shelves, open at the front (-y), its back against the
/// wall at y = `wallY`, centred at x = `cx`.
void addBookcase(SceneBuilder& b, double cx, double wallY, uint32_t material) {
  constexpr double halfWidth = 0.5, depth = 0.35, height = 2.0, board = 0.03;
  const double x0 = cx - halfWidth, x1 = cx + halfWidth, y0 = wallY - depth;
  b.addBox({x0, y0, 0}, {x0 + board, wallY, height}, material);
  b.addBox({x1 - board, y0, 0}, {x1, wallY, height}, material);
  for (int k = 0; k < 5; ++k) {
    const double z = k == 0 ? 0.08 : k == 4 ? height - board : 0.08 + k * 0.45;
    b.addBox({x0 + board, y0, z}, {x1 - board, wallY, z + board}, material);
  }
}

}  // namespace

Scene generateFurnishedRoom(const FurnishedRoomOptions& o) {
  if (!(o.width >= 4) || !(o.depth >= 3.5) || !(o.height >= 2.2) || o.chairs < 0 || o.chairs > 4 ||
      !(o.lightEmission >= 0) || !(o.width <= 1e4 && o.depth <= 1e4 && o.height <= 1e4)) {
    throw std::invalid_argument(
        "room options: width >= 4, depth >= 3.5, height >= 2.2 (metres, at most 1e4), chairs "
        "0..4, emission >= 0");
  }
  Scene scene;
  const uint32_t wall = scene.addMaterial({"wall", {0.7, 0.68, 0.62}, {}});
  const uint32_t floor = scene.addMaterial({"floor", {0.45, 0.32, 0.2}, {}});
  const uint32_t ceiling = scene.addMaterial({"ceiling", {0.8, 0.8, 0.8}, {}});
  const uint32_t table = scene.addMaterial({"table", {0.55, 0.38, 0.22}, {}});
  const uint32_t chair = scene.addMaterial({"chair", {0.3, 0.35, 0.6}, {}});
  const uint32_t shelf = scene.addMaterial({"bookcase", {0.6, 0.5, 0.35}, {}});
  const uint32_t light = scene.addMaterial(
      {"light", {0.8, 0.8, 0.8}, {o.lightEmission, o.lightEmission, o.lightEmission}});

  const double w = o.width, d = o.depth, h = o.height;
  Aabb extent;
  extent.add(Vec3{0, 0, 0});
  extent.add(Vec3{w, d, h});
  SceneBuilder b(scene, Tolerance::forBounds(extent));

  // The room's inside: each face looks into the room.
  b.addAxisRect(2, true, {0, 0, 0}, {w, d, 0}, floor);
  b.addAxisRect(2, false, {0, 0, h}, {w, d, h}, ceiling);
  b.addAxisRect(0, true, {0, 0, 0}, {0, d, h}, wall);
  b.addAxisRect(0, false, {w, 0, 0}, {w, d, h}, wall);
  b.addAxisRect(1, true, {0, 0, 0}, {w, 0, h}, wall);
  b.addAxisRect(1, false, {0, d, 0}, {w, d, h}, wall);

  // The table at the centre, its long side along x; the lights over its two halves.
  const double cx = 0.5 * w, cy = 0.5 * d;
  addTopOnLegs(b, {cx - 0.8, cy - 0.45, 0.72}, {cx + 0.8, cy + 0.45, 0.77}, 0.05, table);
  for (int side = -1; side <= 1; side += 2) {
    const double lx = cx + side * 0.8, z = h - kLightDrop;
    b.addAxisRect(2, false, {lx - 0.5 * kLightSize, cy - 0.5 * kLightSize, z},
                  {lx + 0.5 * kLightSize, cy + 0.5 * kLightSize, z}, light);
  }

  // Chairs: the two long sides first, then the two ends; backs away from the table.
  const struct {
    double x, y;
    int axis, sign;
  } places[4] = {
      {cx, cy - 0.75, 1, -1}, {cx, cy + 0.75, 1, 1}, {cx - 1.15, cy, 0, -1}, {cx + 1.15, cy, 0, 1}};
  for (int k = 0; k < o.chairs; ++k)
    addChair(b, places[k].x, places[k].y, places[k].axis, places[k].sign, chair);

  if (o.bookcase) addBookcase(b, 0.25 * w, d, shelf);
  return scene;
}

}  // namespace gv
