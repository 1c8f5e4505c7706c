// Tests of Quake .map → Scene: outward brush faces, hidden-surface removal between brushes
// (checked against analytic areas), skipped brush kinds, light entities as emitters.
#include "quake/map_to_scene.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>

#include "input/load_scene.h"
#include "quake/brush_csg.h"
#include "quake/map_text.h"
#include "support/run_cli.h"
#include "support/temp_dir.h"
#include "util/input_error.h"

namespace gv {
namespace {

using test::boxBrush;
using test::pointEntity;
using test::world;

Scene convert(const std::string& text, MapImportStats* stats = nullptr,
              const MapImportOptions& o = {}) {
  return mapToScene(parseMapText("t.map", text), "t.map", o, stats);
}

void expectNear(const Vec3& a, const Vec3& b) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-9) << k;
}

double area(const Scene& s) {
  return s.totalArea();
}

/// True when some patch's interior lies in plane `axis = at`.
bool anyPatchOnPlane(const Scene& s, int axis, double at) {
  for (const Patch& p : s.patches) {
    bool on = true;
    for (const Vec3& v : p.polygon.vertices) on = on && std::abs(v[axis] - at) < 1e-9;
    if (on) return true;
  }
  return false;
}

TEST(MapToScene, OneCubeGivesSixOutwardPatches) {
  const Scene s = convert(world(boxBrush({0, 0, 0}, {64, 64, 64})));
  ASSERT_EQ(s.patches.size(), 6u);
  EXPECT_NEAR(area(s), 6 * 64.0 * 64.0, 1e-6);
  const Vec3 c{32, 32, 32};
  for (const Patch& p : s.patches) EXPECT_GT(dot(p.polygon.normal(), p.polygon.centroid() - c), 0);
  const Aabb b = s.bounds();
  expectNear(b.lo, {0, 0, 0});
  expectNear(b.hi, {64, 64, 64});
}

TEST(MapToScene, RealBrushFromQbspfeaturesFacesOut) {
  // Brush 0 of ericw-tools' qbspfeatures.map (Valve 220), written by TrenchBroom: the box
  // x in [-80, 64], y in [64, 80], z in [16, 96] whatever the order of its points.
  const std::string brush =
      "{\n"
      "( -80 256 16 ) ( -80 257 16 ) ( -80 256 17 ) brown_brick [ 0 -1 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "( -64 64 16 ) ( -64 64 17 ) ( -63 64 16 ) brown_brick [ 1 0 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "( -64 256 16 ) ( -63 256 16 ) ( -64 257 16 ) brown_brick [ -1 0 0 0 ] [ 0 -1 0 0 ] 0 1 1\n"
      "( 64 384 96 ) ( 64 385 96 ) ( 65 384 96 ) brown_brick [ 1 0 0 0 ] [ 0 -1 0 0 ] 0 1 1\n"
      "( 64 80 48 ) ( 65 80 48 ) ( 64 80 49 ) brown_brick [ -1 0 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "( 64 384 48 ) ( 64 384 49 ) ( 64 385 48 ) brown_brick [ 0 1 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "}\n";
  const Scene s = convert(world(brush));
  ASSERT_EQ(s.patches.size(), 6u);
  const Aabb b = s.bounds();
  expectNear(b.lo, {-80, 64, 16});
  expectNear(b.hi, {64, 80, 96});
  const Vec3 c = b.center();
  for (const Patch& p : s.patches) EXPECT_GT(dot(p.polygon.normal(), p.polygon.centroid() - c), 0);
  EXPECT_NEAR(area(s), 2 * (144.0 * 16 + 144.0 * 80 + 16.0 * 80), 1e-6);
}

TEST(MapToScene, TouchingBrushesLoseTheSharedFace) {
  MapImportStats st;
  const Scene s =
      convert(world(boxBrush({0, 0, 0}, {64, 64, 64}) + boxBrush({64, 0, 0}, {128, 64, 64})), &st);
  EXPECT_EQ(s.patches.size(), 10u);
  EXPECT_NEAR(area(s), 10 * 64.0 * 64.0, 1e-6);
  EXPECT_FALSE(anyPatchOnPlane(s, 0, 64));
  EXPECT_EQ(st.hiddenFaces, 2u);
}

TEST(MapToScene, PartlyTouchingBrushesKeepTheUncoveredPart) {
  // A small box against the middle of a big one's +x face: the big face keeps a frame around it.
  const Scene s =
      convert(world(boxBrush({0, 0, 0}, {64, 96, 96}) + boxBrush({64, 32, 32}, {96, 64, 64})));
  double onPlane = 0;
  for (const Patch& p : s.patches)
    if (std::abs(p.polygon.centroid().x - 64) < 1e-9) {
      onPlane += p.polygon.area();
      EXPECT_GT(p.polygon.normal().x, 0);
    }
  EXPECT_NEAR(onPlane, 96.0 * 96 - 32.0 * 32, 1e-6);
  EXPECT_NEAR(area(s), 2 * (64.0 * 96 * 2 + 96.0 * 96) + 4 * 32.0 * 32, 1e-6);
}

TEST(MapToScene, NearlyTouchingBrushesAreSnappedShut) {
  // An off-grid brush 0.003 units short of its neighbour (rounded editor output) in a map of
  // Quake size (a far pillar makes the diagonal ~11,000 units: model tolerance ~0.11 units): the
  // planes are merged, the brushes touch and their shared face disappears.
  const std::string far = boxBrush({8000, 8000, 0}, {8064, 8064, 64});
  MapImportStats st;
  const Scene s = convert(
      world(boxBrush({0, 0, 0}, {64, 64, 64}) + boxBrush({64.003, 0, 0}, {128, 64, 64}) + far),
      &st);
  EXPECT_EQ(s.patches.size(), 16u);
  EXPECT_EQ(st.hiddenFaces, 2u);
  EXPECT_NEAR(area(s), 16 * 64.0 * 64.0, 1e-6);
  // A real gap (a unit, beyond the tolerance) stays open.
  const Scene open =
      convert(world(boxBrush({0, 0, 0}, {64, 64, 64}) + boxBrush({65, 0, 0}, {128, 64, 64}) + far));
  EXPECT_EQ(open.patches.size(), 18u);
}

TEST(MapToScene, BrushInsideAnotherGivesNothing) {
  MapImportStats st;
  const Scene s = convert(
      world(boxBrush({0, 0, 0}, {128, 128, 128}) + boxBrush({32, 32, 32}, {64, 64, 64})), &st);
  EXPECT_EQ(s.patches.size(), 6u);
  EXPECT_NEAR(area(s), 6 * 128.0 * 128.0, 1e-6);
  EXPECT_EQ(st.hiddenFaces, 6u);
}

TEST(MapToScene, OverlappingBrushesGiveTheUnionsSurface) {
  // A = [0,64]^3, B = A + (32, 32, 0): the union's surface (tops and bottoms coincide in part:
  // exactly one copy each) is 2 · (2·64² − 32²) + perimeter 6·64 × height 64.
  for (bool reversed : {false, true}) {
    const std::string a = boxBrush({0, 0, 0}, {64, 64, 64}),
                      b = boxBrush({32, 32, 0}, {96, 96, 64});
    const Scene s = convert(world(reversed ? b + a : a + b));
    const double expected = 2 * (2 * 64.0 * 64 - 32.0 * 32) + 6 * 64.0 * 64;
    EXPECT_NEAR(area(s), expected, 1e-6) << reversed;
    // No point of a patch lies strictly inside either box (an independent check of the cut).
    for (const Patch& p : s.patches) {
      const Vec3 c = p.polygon.centroid();
      for (const auto& [lo, hi] : {std::pair{Vec3{0, 0, 0}, Vec3{64, 64, 64}},
                                   std::pair{Vec3{32, 32, 0}, Vec3{96, 96, 64}}}) {
        const bool inside = c.x > lo.x + 1e-6 && c.x < hi.x - 1e-6 && c.y > lo.y + 1e-6 &&
                            c.y < hi.y - 1e-6 && c.z > lo.z + 1e-6 && c.z < hi.z - 1e-6;
        EXPECT_FALSE(inside);
      }
    }
  }
}

TEST(MapToScene, RandomBoxUnionsMatchAVoxelOracle) {
  // Seeded random boxes on an integer grid (so they overlap, touch face to face and share
  // coplanar faces often): the patches must tile exactly the boundary of the union, which the
  // voxels of the grid give exactly: every voxel face between a full and an empty voxel, each
  // patch in front of air and behind solid.
  constexpr int kGrid = 8;
  constexpr double kUnit = 16;
  std::mt19937 rng(20261201);
  size_t hiddenTotal = 0, cutTotal = 0;
  for (int round = 0; round < 200; ++round) {
    std::uniform_int_distribution<int> count(2, 8), coord(0, kGrid);
    std::vector<std::pair<std::array<int, 3>, std::array<int, 3>>> boxes;
    std::string brushes;
    const int n = count(rng);
    while (static_cast<int>(boxes.size()) < n) {
      std::array<int, 3> lo{}, hi{};
      for (int k = 0; k < 3; ++k) {
        int a = coord(rng), b = coord(rng);
        if (a == b) b = a < kGrid ? a + 1 : a - 1;
        lo[k] = std::min(a, b);
        hi[k] = std::max(a, b);
      }
      boxes.emplace_back(lo, hi);
      brushes += boxBrush(Vec3{lo[0] * kUnit, lo[1] * kUnit, lo[2] * kUnit},
                          Vec3{hi[0] * kUnit, hi[1] * kUnit, hi[2] * kUnit});
    }
    auto full = [&](int x, int y, int z) {
      if (x < 0 || y < 0 || z < 0 || x >= kGrid || y >= kGrid || z >= kGrid) return false;
      for (const auto& [lo, hi] : boxes)
        if (x >= lo[0] && x < hi[0] && y >= lo[1] && y < hi[1] && z >= lo[2] && z < hi[2])
          return true;
      return false;
    };
    size_t boundaryFaces = 0;
    for (int x = -1; x < kGrid; ++x)
      for (int y = -1; y < kGrid; ++y)
        for (int z = -1; z < kGrid; ++z) {
          boundaryFaces += full(x, y, z) != full(x + 1, y, z);
          boundaryFaces += full(x, y, z) != full(x, y + 1, z);
          boundaryFaces += full(x, y, z) != full(x, y, z + 1);
        }
    MapImportStats st;
    const Scene s = convert(world(brushes), &st);
    hiddenTotal += st.hiddenFaces;
    cutTotal += st.cutFaces;
    EXPECT_NEAR(area(s), static_cast<double>(boundaryFaces) * kUnit * kUnit, 1e-6)
        << "round " << round;
    for (const Patch& p : s.patches) {
      const Vec3 c = p.polygon.centroid(), nrm = p.polygon.normal();
      auto voxel = [&](const Vec3& q) {
        return full(static_cast<int>(std::floor(q.x / kUnit)),
                    static_cast<int>(std::floor(q.y / kUnit)),
                    static_cast<int>(std::floor(q.z / kUnit)));
      };
      // Centroids of the patches may fall on voxel edges; nudge inside the patch a little.
      const Vec3 q = c + (p.polygon.vertices[0] - c) * 1e-3;
      EXPECT_FALSE(voxel(q + nrm * 0.5)) << "round " << round << ": patch faces solid";
      EXPECT_TRUE(voxel(q - nrm * 0.5)) << "round " << round << ": patch has air behind";
    }
  }
  // The generator is not trivial: faces are hidden and cut.
  EXPECT_GT(hiddenTotal, 200u);
  EXPECT_GT(cutTotal, 200u);
}

/// A uniformly random point of a convex polygon (fan triangles chosen by area).
Vec3 samplePolygon(const ConvexPolygon& poly, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<Vec3>& v = poly.vertices;
  double total = 0;
  std::vector<double> cumulative;
  for (size_t i = 1; i + 1 < v.size(); ++i) {
    total += length(cross(v[i] - v[0], v[i + 1] - v[0]));
    cumulative.push_back(total);
  }
  const double pick = u(rng) * total;
  size_t t = 0;
  while (t + 1 < cumulative.size() && cumulative[t] < pick) ++t;
  double a = u(rng), b = u(rng);
  if (a + b > 1) {
    a = 1 - a;
    b = 1 - b;
  }
  return v[0] + (v[t + 1] - v[0]) * a + (v[t + 2] - v[0]) * b;
}

TEST(MapToScene, RandomSlantedBrushesAgainstPointSampling) {
  // Seeded random convex brushes (8-14 planes tangent to a ball, slanted directions) that
  // overlap: every sampled point of a patch lies outside all brushes, and every sampled point of
  // a brush face outside all other brushes lies on some patch. Exact point tests, no statistics.
  std::mt19937 rng(99);
  std::normal_distribution<double> gauss(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  size_t checkedVisible = 0, checkedPatches = 0;
  for (int round = 0; round < 40; ++round) {
    std::string brushes;
    const int count = 3 + round % 4;
    for (int b = 0; b < count; ++b) {
      const Vec3 c{u(rng) * 96, u(rng) * 96, u(rng) * 96};
      const double r = 32 + 32 * u(rng);
      brushes += "{\n";
      // A randomly rotated box's six directions (so the brush is bounded) plus 2-8 random ones.
      const Vec3 a = normalize(Vec3{gauss(rng), gauss(rng), gauss(rng)});
      const Vec3 e = normalize(cross(a, Vec3{gauss(rng), gauss(rng), gauss(rng)}));
      std::vector<Vec3> normals = {a, -a, e, -e, cross(a, e), -cross(a, e)};
      const int extra = 2 + static_cast<int>(rng() % 7);
      for (int k = 0; k < extra; ++k)
        normals.push_back(normalize(Vec3{gauss(rng), gauss(rng), gauss(rng)}));
      for (const Vec3& n : normals) {
        const Vec3 t1 =
            normalize(std::abs(n.x) < 0.9 ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0}));
        const Vec3 t2 = cross(n, t1);  // cross(t1, t2) = n
        const Vec3 p1 = c + n * r, p0 = p1 + t1 * 64, p2 = p1 + t2 * 64;
        char line[512];
        std::snprintf(
            line, sizeof line,
            "( %.17g %.17g %.17g ) ( %.17g %.17g %.17g ) ( %.17g %.17g %.17g ) w 0 0 0 1 1\n", p0.x,
            p0.y, p0.z, p1.x, p1.y, p1.z, p2.x, p2.y, p2.z);
        brushes += line;
      }
      brushes += "}\n";
    }
    const MapFile map = parseMapText("r.map", world(brushes));
    const Scene s = mapToScene(map, "r.map");
    const Tolerance tol = s.tolerance();
    std::vector<BrushSolid> solids;
    for (const MapBrush& b : map.entities[0].brushes) {
      std::optional<BrushSolid> solid = brushSolid(b, tol);
      ASSERT_TRUE(solid);  // bounded: it has a rotated box's six planes
      solids.push_back(std::move(*solid));
    }
    const double margin = 1e-6 * tol.scale;  // points this close to another solid are skipped
    auto depthIn = [&](const BrushSolid& b, const Vec3& p) {  // > 0 inside, < 0 outside
      double d = INFINITY;
      for (const Plane& h : b.shape.halfspaces) d = std::min(d, -h.distance(p));
      return d;
    };
    for (const Patch& p : s.patches)
      for (int k = 0; k < 20; ++k) {
        const Vec3 q = samplePolygon(p.polygon, rng);
        for (const BrushSolid& b : solids) EXPECT_LT(depthIn(b, q), margin) << "round " << round;
        ++checkedPatches;
      }
    for (size_t i = 0; i < solids.size(); ++i)
      for (const PolyhedronFace& f : solids[i].shape.faces)
        for (int k = 0; k < 20; ++k) {
          const Vec3 q = samplePolygon(f.polygon, rng);
          bool outside = true;
          for (size_t j = 0; j < solids.size() && outside; ++j)
            if (j != i) outside = depthIn(solids[j], q) < -margin;
          if (!outside) continue;
          bool covered = false;
          for (const Patch& p : s.patches) covered = covered || p.polygon.contains(q, tol);
          EXPECT_TRUE(covered) << "round " << round << " brush " << i;
          ++checkedVisible;
        }
  }
  EXPECT_GT(checkedVisible, 2000u);
  EXPECT_GT(checkedPatches, 2000u);
}

TEST(MapToScene, NonSolidBrushesAreSkippedAndSkyIsBlack) {
  MapImportStats st;
  const std::string text =
      world(boxBrush({0, 0, 0}, {64, 64, 64}) + boxBrush({200, 0, 0}, {264, 64, 64}, "sky4") +
            boxBrush({400, 0, 0}, {464, 64, 64}, "clip") +
            boxBrush({600, 0, 0}, {664, 64, 64}, "*water1") +
            boxBrush({800, 0, 0}, {864, 64, 64}, "hint") +
            boxBrush({1000, 0, 0}, {1064, 64, 64}, "skip") +
            boxBrush({1200, 0, 0}, {1264, 64, 64}, "origin") +
            boxBrush({1400, 0, 0}, {1464, 64, 64}, "trigger")) +
      "{\n\"classname\" \"trigger_once\"\n" + boxBrush({0, 200, 0}, {64, 264, 64}) + "}\n" +
      "{\n\"classname\" \"func_illusionary\"\n" + boxBrush({0, 400, 0}, {64, 464, 64}) + "}\n" +
      "{\n\"classname\" \"func_detail\"\n" + boxBrush({0, 600, 0}, {64, 664, 64}) + "}\n";
  const Scene s = convert(text, &st);
  EXPECT_EQ(s.patches.size(), 18u);  // wall, sky and func_detail boxes
  EXPECT_EQ(st.skyFaces, 6u);
  EXPECT_EQ(st.skyBrushes, 1u);
  EXPECT_EQ(st.clipBrushes, 1u);
  EXPECT_EQ(st.liquidBrushes, 1u);
  EXPECT_EQ(st.hintBrushes, 1u);
  EXPECT_EQ(st.skipOnlyBrushes, 1u);
  EXPECT_EQ(st.originBrushes, 1u);
  EXPECT_EQ(st.triggerBrushes, 1u);
  EXPECT_EQ(st.nonSolidEntityBrushes, 2u);
  size_t black = 0;
  for (const Patch& p : s.patches) {
    const Material& m = s.materials[p.material];
    EXPECT_FALSE(m.isEmitter());
    if (m.reflectance.isBlack()) {
      ++black;
      EXPECT_GT(p.polygon.centroid().x, 199);
    } else {
      EXPECT_GE(m.reflectance.r, 0.25);
      EXPECT_LE(m.reflectance.r, 0.8);
    }
  }
  EXPECT_EQ(black, 6u);
  EXPECT_FALSE(s.report.warnings.empty());
}

TEST(MapToScene, SkipFacesAreNotDrawnButStillHide) {
  // A skip-bottomed box standing on a floor: its bottom is not drawn, and the floor under it is
  // hidden all the same (the box is solid).
  std::string sides;
  for (int k = 0; k < 3; ++k) {
    sides += test::boxSide(k, -1, 0, k == 2 ? "skip" : "wall");
    sides += test::boxSide(k, +1, 64, "wall");
  }
  MapImportStats st;
  const Scene s =
      convert(world("{\n" + sides + "}\n" + boxBrush({-64, -64, -16}, {128, 128, 0})), &st);
  EXPECT_EQ(st.skipFaces, 1u);
  EXPECT_EQ(st.hiddenFaces, 0u);
  EXPECT_EQ(st.cutFaces, 1u);  // the floor's top
  EXPECT_NEAR(area(s), 5 * 64.0 * 64 + (2 * 192.0 * 192 - 64.0 * 64) + 4 * 192.0 * 16, 1e-6);
}

TEST(MapToScene, ClosedDetailWallCutsOnlyWhereAFaceLiesFlatAgainstIt) {
  // One func_detail_wall of three stacked boxes on a world floor, under a world box, with a world
  // box poking into its lower box from the side. Faces covered whole are dropped: those between
  // its two big boxes, the world box's bottom on its small box, the poking box's end inside it
  // (on e3m4 such faces, flush with another brush's side, let `verify`'s rays out across that side
  // within the contact distance). Faces flat against it in part lose that part: the upper box's
  // top under the small box and the floor's top under the stack (e3m4: the buried part of a beam's
  // bottom did the same). A face passing through it stays whole (func_detail_wall clips nothing):
  // the poking box's sides. The world's brushes hide and cut as usual: the lower box's bottom and
  // the small box's top go, the lower box's side loses the poking box's section.
  const std::string detail =
      "{\n\"classname\" \"func_detail_wall\"\n" + boxBrush({0, 0, 0}, {64, 64, 64}) +
      boxBrush({0, 0, 64}, {64, 64, 128}) + boxBrush({0, 0, 128}, {32, 32, 160}) + "}\n";
  MapImportStats st;
  const Scene s =
      convert(world(boxBrush({-64, -64, -16}, {128, 128, 0}) +
                    boxBrush({0, 0, 160}, {32, 32, 192}) + boxBrush({48, 16, 16}, {96, 48, 48})) +
                  detail,
              &st);
  EXPECT_FALSE(anyPatchOnPlane(s, 2, 64));
  EXPECT_FALSE(anyPatchOnPlane(s, 2, 160));
  double onTop = 0, onFloor = 0, pokeSides = 0;
  for (const Patch& p : s.patches) {
    const Vec3 c = p.polygon.centroid();
    const double a = p.polygon.area();
    if (std::abs(c.z - 128) < 1e-9) onTop += a * p.polygon.normal().z;
    if (std::abs(c.z) < 1e-9) onFloor += a * p.polygon.normal().z;
    if (c.z > 0 && c.z < 64 && c.x > 64 && c.x < 96 && std::abs(p.polygon.normal().x) < 1e-9)
      pokeSides += a;
  }
  EXPECT_NEAR(onTop, 64.0 * 64 - 32.0 * 32, 1e-6);      // the upper box's top, facing up, cut
  EXPECT_NEAR(onFloor, 192.0 * 192 - 64.0 * 64, 1e-6);  // the floor's top, cut
  // Each of the poking box's four sides is whole (48 × 32; centroid at x = 72), not cut at x = 64.
  EXPECT_NEAR(pokeSides, 4 * 48.0 * 32, 1e-6);
  EXPECT_EQ(st.hiddenFaces, 7u);
  EXPECT_EQ(st.cutFaces, 3u);  // the upper top, the floor's top, the lower box's side
  // The floor brush but the stack's footprint; the big boxes' sides (one with a hole) and the upper
  // top but the small box's footprint; the small box's sides; the world box but its bottom; the
  // poking box but its end.
  EXPECT_NEAR(area(s),
              (2 * 192.0 * 192 + 4 * 192.0 * 16 - 64.0 * 64) + (9 * 64.0 * 64 - 2 * 32.0 * 32) +
                  4 * 32.0 * 32 + 5 * 32.0 * 32 + (4 * 48.0 * 32 + 32.0 * 32),
              1e-6);
}

TEST(MapToScene, DetailWallBrushWithASkipSideHidesNothing) {
  // Two stacked func_detail_wall boxes, the upper with a skip side: the upper box is open, so
  // the lower one's top stays (seen through the opening); the lower, closed, still hides the
  // upper one's bottom.
  std::string open;
  for (int k = 0; k < 3; ++k) {
    open += test::boxSide(k, -1, k == 2 ? 64 : 0, "wall");
    open += test::boxSide(k, +1, k == 2 ? 128 : 64, k == 0 ? "skip" : "wall");
  }
  const std::string detail = "{\n\"classname\" \"func_detail_wall\"\n" +
                             boxBrush({0, 0, 0}, {64, 64, 64}) + "{\n" + open + "}\n}\n";
  MapImportStats st;
  const Scene s = convert(world("") + detail, &st);
  std::vector<double> at64;
  for (const Patch& p : s.patches)
    if (std::abs(p.polygon.centroid().z - 64) < 1e-9)
      at64.push_back(p.polygon.area() * p.polygon.normal().z);
  EXPECT_EQ(at64, std::vector<double>{64.0 * 64});  // the lower top, facing up
  EXPECT_EQ(st.skipFaces, 1u);
  EXPECT_EQ(st.hiddenFaces, 1u);
}

TEST(MapToScene, LightEntityBecomesAnEmittingCube) {
  MapImportStats st;
  const std::string text =
      world(boxBrush({-512, -512, -64}, {512, 512, -32})) +
      pointEntity("light", {0, 0, 64}, "\"light\" \"200\"\n") +
      pointEntity("light_torch_small_walltorch", {100, 0, 64}) +
      pointEntity("light", {-100, 0, 64}, "\"_color\" \"255 128 0\"\n") +
      pointEntity("monster_soldier_light", {0, 100, 64}) +
      pointEntity("light", {0, -100, 64}, "\"light\" \"-50\"\n") +
      pointEntity("light", {0, -200, 64}, "\"targetname\" \"t1\"\n\"spawnflags\" \"1\"\n") +
      pointEntity("light", {0, -300, 64}, "\"spawnflags\" \"1\"\n");
  const Scene s = convert(text, &st);
  EXPECT_EQ(st.lights, 4u);  // spawnflags 1 without a targetname is not a switchable light
  EXPECT_EQ(st.skippedLights, 1u);
  EXPECT_EQ(st.startOffLights, 1u);
  // Emitted power per light: Ke × area over its patches, = kQuakeLightPowerPerValue × light.
  std::map<int, double> power;  // keyed by the cube's x + 10 y, in hundreds of units
  std::map<int, Rgb> colour;
  for (const Patch& p : s.patches) {
    const Material& m = s.materials[p.material];
    if (!m.isEmitter()) continue;
    const int x = static_cast<int>(std::lround(p.polygon.centroid().x / 100) +
                                   10 * std::lround(p.polygon.centroid().y / 100));
    power[x] += m.emission.r * p.polygon.area();
    colour[x] = m.emission;
    EXPECT_NEAR(p.polygon.centroid().z, 64, 4 + 1e-9);
  }
  ASSERT_EQ(power.size(), 4u);
  EXPECT_NEAR(power[0], kQuakeLightPowerPerValue * 200, 1e-6);
  EXPECT_NEAR(power[1], kQuakeLightPowerPerValue * kQuakeDefaultLight, 1e-6);
  EXPECT_NEAR(power[-1], kQuakeLightPowerPerValue * kQuakeDefaultLight, 1e-6);
  EXPECT_NEAR(colour[-1].g / colour[-1].r, 128.0 / 255.0, 1e-12);
  EXPECT_EQ(colour[-1].b, 0);
  EXPECT_NEAR(power[-30], kQuakeLightPowerPerValue * kQuakeDefaultLight, 1e-6);
  EXPECT_EQ(s.emitterCount(), 24u);
}

TEST(MapToScene, SurfaceLightTemplatesMakeTheirTextureEmit) {
  // A light with "_surface" (ericw-tools) is no point light: every face textured like it emits
  // the template's power per spacing² of area. Textures are matched ignoring case.
  MapImportStats st;
  const std::string text =
      world(boxBrush({0, 0, 0}, {64, 64, 64}) +
            boxBrush({200, 0, 0}, {264, 64, 64}, "BrownLight")) +
      pointEntity("light", {0, 0, 300}, "\"_surface\" \"brownlight\"\n\"light\" \"200\"\n") +
      pointEntity("light", {0, 0, 300},
                  "\"_surface\" \"wall\"\n\"light\" \"100\"\n\"_surface_spacing\" \"64\"\n"
                  "\"_color\" \"0 0 1\"\n");
  const Scene s = convert(text, &st);
  EXPECT_EQ(st.surfaceLights, 2u);
  EXPECT_EQ(st.lights, 0u);
  EXPECT_EQ(st.surfaceLightPatches, 12u);
  EXPECT_EQ(s.patches.size(), 12u);  // no cubes
  for (const Patch& p : s.patches) {
    const Rgb e = s.materials[p.material].emission;
    if (p.polygon.centroid().x > 100) {
      EXPECT_NEAR(e.r, kQuakeLightPowerPerValue * 200 / (128.0 * 128), 1e-9);
      EXPECT_EQ(e.r, e.b);
    } else {
      EXPECT_EQ(e.r, 0);
      EXPECT_NEAR(e.b, kQuakeLightPowerPerValue * 100 / (64.0 * 64), 1e-9);
    }
  }
}

TEST(MapToScene, LightCubeInsideAWallKeepsOnlyItsOutsidePart) {
  // The cube [-4, 4]^3 around the origin against a wall filling x <= 0: the -x face and the
  // halves of four faces inside the wall go.
  const Scene s =
      convert(world(boxBrush({-64, -64, -64}, {0, 64, 64})) + pointEntity("light", {0, 0, 0}));
  double emitting = 0;
  for (const Patch& p : s.patches)
    if (s.materials[p.material].isEmitter()) {
      emitting += p.polygon.area();
      EXPECT_GE(p.polygon.centroid().x, 0);
    }
  EXPECT_NEAR(emitting, 64 + 4 * 32, 1e-9);
}

TEST(MapToScene, DegenerateBrushesAreDroppedAndCounted) {
  const std::string collinear = "{\n( 0 0 0 ) ( 1 1 1 ) ( 2 2 2 ) wall 0 0 0 1 1\n" +
                                test::boxSide(0, 1, 64, "wall") + test::boxSide(1, 1, 64, "wall") +
                                test::boxSide(2, 1, 64, "wall") + "}\n";
  const std::string open = "{\n" + test::boxSide(0, 1, 64, "wall") +
                           test::boxSide(1, 1, 64, "wall") + test::boxSide(2, 1, 64, "wall") +
                           test::boxSide(2, -1, 0, "wall") + "}\n";
  const std::string empty = "{\n" + test::boxSide(0, 1, 0, "wall") +
                            test::boxSide(0, -1, 64, "wall") + test::boxSide(1, 1, 64, "wall") +
                            test::boxSide(1, -1, 0, "wall") + test::boxSide(2, 1, 64, "wall") +
                            test::boxSide(2, -1, 0, "wall") + "}\n";
  MapImportStats st;
  const Scene s = convert(world(collinear + open + empty + boxBrush({0, 0, 0}, {64, 64, 64})), &st);
  EXPECT_EQ(st.degenerateBrushes, 3u);
  EXPECT_EQ(s.patches.size(), 6u);
  bool warned = false;
  for (const std::string& w : s.report.warnings)
    warned = warned || w.find("degenerate brush") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(MapToScene, MoversCanBeLeftOut) {
  const std::string text = world(boxBrush({0, 0, 0}, {64, 64, 64})) +
                           "{\n\"classname\" \"func_door\"\n" +
                           boxBrush({0, 200, 0}, {64, 264, 64}) + "}\n";
  EXPECT_EQ(convert(text).patches.size(), 12u);
  MapImportOptions o;
  o.includeMovers = false;
  EXPECT_EQ(convert(text, nullptr, o).patches.size(), 6u);
}

TEST(MapToScene, BadEntitiesAndEmptyMapsAreInputErrors) {
  EXPECT_THROW(convert(world("")), InputError);
  EXPECT_THROW(convert(world(boxBrush({0, 0, 0}, {64, 64, 64}, "clip"))), InputError);
  try {
    convert(world(boxBrush({0, 0, 0}, {64, 64, 64})) +
            "{\n\"classname\" \"light\"\n\"origin\" \"1 2\"\n}\n");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 13u);  // the light entity's brace
  }
  EXPECT_THROW(convert(world(boxBrush({0, 0, 0}, {64, 64, 64})) +
                       pointEntity("light", {0, 0, 100}, "\"light\" \"bright\"\n")),
               InputError);
}

TEST(MapToScene, LoadSceneAndTheCliTakeMapFiles) {
  const auto dir = test::scratchDir();
  const std::string path =
      test::writeFile(dir / "room.map", world(boxBrush({0, 0, 0}, {64, 64, 64})) +
                                            pointEntity("light", {32, 32, 100}));
  const Scene s = loadScene(path);
  EXPECT_EQ(s.patches.size(), 12u);
  const test::CliResult r = test::runCli("info '" + path + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("patches      12"), std::string::npos) << r.output;
  const std::string bad = test::writeFile(dir / "bad.map", "{\n{\n( 0 0 0 ) oops\n}\n}\n");
  const test::CliResult rb = test::runCli("info '" + bad + "'");
  EXPECT_EQ(rb.exitCode, 2) << rb.output;
  EXPECT_NE(rb.output.find("bad.map:3"), std::string::npos) << rb.output;
}

TEST(MapToScene, VisAndVerifyRunOnAMap) {
  // A closed room (six 16-unit walls) with a pillar and a light: `vis` reads the .map and its
  // result passes the Embree ray check of `verify`.
  const auto dir = test::scratchDir();
  const std::vector<std::pair<Vec3, Vec3>> walls = {
      {{-16, -16, -16}, {0, 272, 272}}, {{256, -16, -16}, {272, 272, 272}},
      {{0, -16, -16}, {256, 0, 272}},   {{0, 256, -16}, {256, 272, 272}},
      {{0, 0, -16}, {256, 256, 0}},     {{0, 0, 256}, {256, 256, 272}},
      {{96, 0, 0}, {160, 128, 200}}};
  std::string brushes;
  for (const auto& [lo, hi] : walls) brushes += boxBrush(lo, hi);
  const std::string path =
      test::writeFile(dir / "room.map", world(brushes) + pointEntity("light", {128, 200, 200}));
  const std::string out = (dir / "vis").string();
  const test::CliResult vis = test::runCli("vis '" + path + "' -o '" + out + "'");
  ASSERT_EQ(vis.exitCode, 0) << vis.output;
  const test::CliResult verify = test::runCli("verify '" + out + "'");
  EXPECT_EQ(verify.exitCode, 0) << verify.output;
  EXPECT_NE(verify.output.find("OK"), std::string::npos) << verify.output;
}

}  // namespace
}  // namespace gv
