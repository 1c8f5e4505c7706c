// INVISIBLE pairs against an exact answer (issue #17): two empty box rooms side by side, joined by
// a doorway in the zero-thickness wall between them, every surface cut into patches of about
// half a unit, read through the OBJ importer. There a pair (S in one room, R in the other) has a
// free segment exactly when the section of conv(S′ ∪ R′) by the wall's plane overlaps the open
// doorway, S′ and R′ being the parts of S and R in front of each other: a segment from S′ to R′
// crosses the wall once, inside the section, and inside the rooms it meets nothing (each room is
// convex and empty). Within a room every facing pair sees. So the pairs of the scene are decided
// by hand-checkable geometry, shared with nothing in the visibility code, not by sampling; only
// those whose section passes within kMargin of the doorway's edge (876 of 56,644) are left open.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>

#include "bsp/subdivision.h"
#include "input/load_scene.h"
#include "radiosity/polygon_sampling.h"
#include "raycast/embree_scene.h"
#include "support/temp_dir.h"
#include "visibility/propagation.h"

namespace gv {
namespace {

// Rooms A: x in [-4, 0], B: x in [0, 4]; both y in [0, 3], z in [0, 2.5]; the doorway in x = 0.
constexpr double kDoorY0 = 1.2, kDoorY1 = 1.8, kDoorZ1 = 2.0;
/// How far inside (outside) the doorway's edges a section must reach to count as surely
/// visible (surely invisible): ten times the model tolerance of this 8.6-unit scene (1e-5 of its
/// diagonal), within which `vis` may treat a contact either way.
constexpr double kMargin = 1e-3;
/// Patch size of the grid each surface is cut into.
constexpr double kCell = 0.5;

/// Writes the rooms as OBJ: each axis-aligned rectangle (corner, two edges) cut into a grid and
/// wound counter-clockwise about `normal`.
void writeRooms(const std::filesystem::path& path) {
  std::ofstream obj(path);
  obj.precision(17);
  obj << "mtllib rooms.mtl\nusemtl grey\n";
  size_t next = 1;
  auto rect = [&](Vec3 p, Vec3 e1, Vec3 e2, const Vec3& normal) {
    if (dot(cross(e1, e2), normal) < 0) std::swap(e1, e2);
    const int n1 = std::max(1, int(std::ceil(length(e1) / kCell - 1e-9)));
    const int n2 = std::max(1, int(std::ceil(length(e2) / kCell - 1e-9)));
    for (int i = 0; i < n1; ++i)
      for (int j = 0; j < n2; ++j) {
        const Vec3 a = p + e1 * (double(i) / n1) + e2 * (double(j) / n2);
        const Vec3 u = e1 * (1.0 / n1), v = e2 * (1.0 / n2);
        for (const Vec3& q : {a, a + u, a + u + v, a + v})
          obj << "v " << q.x << " " << q.y << " " << q.z << "\n";
        obj << "f " << next << " " << next + 1 << " " << next + 2 << " " << next + 3 << "\n";
        next += 4;
      }
  };
  for (const double side : {-1.0, 1.0}) {  // room A (x < 0), then room B (x > 0)
    const double x0 = std::min(0.0, 4 * side), w = 4;
    const Vec3 in{-side, 0, 0};                            // from the far wall towards the middle
    rect({x0, 0, 0}, {w, 0, 0}, {0, 3, 0}, {0, 0, 1});     // floor
    rect({x0, 0, 2.5}, {w, 0, 0}, {0, 3, 0}, {0, 0, -1});  // ceiling
    rect({x0, 0, 0}, {w, 0, 0}, {0, 0, 2.5}, {0, 1, 0});   // y = 0
    rect({x0, 3, 0}, {w, 0, 0}, {0, 0, 2.5}, {0, -1, 0});  // y = 3
    rect({4 * side, 0, 0}, {0, 3, 0}, {0, 0, 2.5}, in);    // the far wall
    const Vec3 out = in * -1.0;                            // the middle wall faces the room
    rect({0, 0, 0}, {0, kDoorY0, 0}, {0, 0, 2.5}, out);
    rect({0, kDoorY1, 0}, {0, 3 - kDoorY1, 0}, {0, 0, 2.5}, out);
    rect({0, kDoorY0, kDoorZ1}, {0, kDoorY1 - kDoorY0, 0}, {0, 0, 2.5 - kDoorZ1}, out);
  }
  std::ofstream(path.parent_path() / "rooms.mtl") << "newmtl grey\nKd 0.5 0.5 0.5\n";
}

using Point2 = std::pair<double, double>;  // (y, z) in the wall's plane

double cross2(const Point2& o, const Point2& a, const Point2& b) {
  return (a.first - o.first) * (b.second - o.second) - (a.second - o.second) * (b.first - o.first);
}

/// Convex hull, counter-clockwise (Andrew's monotone chain).
std::vector<Point2> hull2(std::vector<Point2> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Point2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

/// Area of convex polygon `poly` inside the rectangle [y0, y1] x [z0, z1] (Sutherland-Hodgman).
double areaInRectangle(std::vector<Point2> poly, double y0, double y1, double z0, double z1) {
  auto clip = [&](auto inside, auto meet) {
    std::vector<Point2> out;
    for (size_t i = 0; i < poly.size(); ++i) {
      const Point2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
      if (inside(a)) out.push_back(a);
      if (inside(a) != inside(b)) out.push_back(meet(a, b));
    }
    poly = std::move(out);
  };
  auto onY = [](double y) {
    return [y](const Point2& a, const Point2& b) {
      return Point2{y, a.second + (b.second - a.second) * (y - a.first) / (b.first - a.first)};
    };
  };
  auto onZ = [](double z) {
    return [z](const Point2& a, const Point2& b) {
      return Point2{a.first + (b.first - a.first) * (z - a.second) / (b.second - a.second), z};
    };
  };
  clip([=](const Point2& p) { return p.first >= y0; }, onY(y0));
  clip([=](const Point2& p) { return p.first <= y1; }, onY(y1));
  clip([=](const Point2& p) { return p.second >= z0; }, onZ(z0));
  clip([=](const Point2& p) { return p.second <= z1; }, onZ(z1));
  double area = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Point2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
    area += a.first * b.second - b.first * a.second;
  }
  return std::abs(area) / 2;
}

/// The part of convex polygon `v` on the front of plane (n, through o), closed; empty when
/// nothing of it lies strictly in front.
std::vector<Vec3> frontPart(const std::vector<Vec3>& v, const Vec3& n, const Vec3& o) {
  std::vector<double> d;
  for (const Vec3& p : v) d.push_back(dot(n, p - o));
  if (*std::max_element(d.begin(), d.end()) <= 1e-12) return {};
  std::vector<Vec3> out;
  for (size_t i = 0; i < v.size(); ++i) {
    const size_t j = (i + 1) % v.size();
    if (d[i] >= 0) out.push_back(v[i]);
    if ((d[i] > 0 && d[j] < 0) || (d[i] < 0 && d[j] > 0))
      out.push_back(v[i] + (v[j] - v[i]) * (d[i] / (d[i] - d[j])));
  }
  return out;
}

/// The exact verdict for S in room A and R in room B: the area of the section of conv(S′ ∪ R′)
/// by x = 0 inside the doorway shrunk by kMargin (> 0: surely visible) and grown by it (0:
/// surely invisible).
struct Verdict {
  double inShrunk = 0, inGrown = 0;
};
Verdict acrossTheDoor(const Patch& s, const Patch& r) {
  const ConvexPolygon &sp = s.polygon, &rp = r.polygon;
  const std::vector<Vec3> a = frontPart(sp.vertices, rp.plane.normal, rp.vertices[0]);
  const std::vector<Vec3> b = frontPart(rp.vertices, sp.plane.normal, sp.vertices[0]);
  if (a.empty() || b.empty()) return {};
  std::vector<Point2> section;
  for (const Vec3& u : a)
    if (u.x == 0) section.push_back({u.y, u.z});
  for (const Vec3& v : b)
    if (v.x == 0) section.push_back({v.y, v.z});
  for (const Vec3& u : a)
    for (const Vec3& v : b)
      if (u.x < 0 && v.x > 0) {
        const double t = -u.x / (v.x - u.x);
        section.push_back({u.y + t * (v.y - u.y), u.z + t * (v.z - u.z)});
      }
  const std::vector<Point2> h = hull2(section);
  if (h.size() < 3) return {};
  return {areaInRectangle(h, kDoorY0 + kMargin, kDoorY1 - kMargin, kMargin, kDoorZ1 - kMargin),
          areaInRectangle(h, kDoorY0 - kMargin, kDoorY1 + kMargin, -kMargin, kDoorZ1 + kMargin)};
}

/// Which room a patch bounds: the side of the middle wall its front looks into.
int roomOf(const Patch& p) {
  const Vec3 c = p.polygon.centroid();
  if (c.x != 0) return c.x < 0 ? 0 : 1;
  return p.polygon.plane.normal.x < 0 ? 0 : 1;
}

TEST(ExactInvisibility, EveryPairOfTwoRoomsAndADoorwayAgainstTheSectionOfItsHull) {
  const auto dir = test::scratchDir();
  writeRooms(dir / "rooms.obj");
  const Scene scene = loadScene((dir / "rooms.obj").string());
  ASSERT_GT(scene.patches.size(), 400u);
  const VisibilityGraph graph = computeVisibility(scene, buildVisibilitySubdivision(scene, {}));
  std::set<std::pair<uint32_t, uint32_t>> listed;
  for (const Interaction& in : graph.interactions) listed.insert({in.s, in.r});

  size_t across = 0, surelyVisible = 0, surelyInvisible = 0, unlistedInvisible = 0;
  size_t listedInvisible = 0, sameRoomFacing = 0, missed = 0;
  std::vector<std::pair<uint32_t, uint32_t>> visibleSample, invisibleSample;
  std::string firstMiss;
  const auto n = static_cast<uint32_t>(scene.patches.size());
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t j = i + 1; j < n; ++j) {
      const Patch &p = scene.patches[i], &q = scene.patches[j];
      const bool isListed = listed.count({i, j}) > 0;
      if (roomOf(p) == roomOf(q)) {
        // One convex empty room: a pair sees exactly when each has a part in front of the other.
        const bool faces =
            !frontPart(p.polygon.vertices, q.polygon.plane.normal, q.polygon.vertices[0]).empty() &&
            !frontPart(q.polygon.vertices, p.polygon.plane.normal, p.polygon.vertices[0]).empty();
        if (!faces) continue;
        ++sameRoomFacing;
        if (!isListed && ++missed == 1) firstMiss = fmt::format("same room {} {}", i, j);
        continue;
      }
      ++across;
      const bool aFirst = roomOf(p) == 0;
      const Verdict v = aFirst ? acrossTheDoor(p, q) : acrossTheDoor(q, p);
      if (v.inShrunk > 1e-12 || !(v.inGrown > 0)) {
        // The verdict itself against ray casting, on every 50th pair it decides.
        if ((across % 50) == 0)
          (v.inShrunk > 1e-12 ? visibleSample : invisibleSample).push_back({i, j});
      }
      if (v.inShrunk > 1e-12) {
        ++surelyVisible;
        if (!isListed && ++missed == 1) firstMiss = fmt::format("across {} {}", i, j);
      } else if (!(v.inGrown > 0)) {
        ++surelyInvisible;
        if (isListed)
          ++listedInvisible;
        else
          ++unlistedInvisible;
      }
    }
  }
  std::printf(
      "%u patches: %zu facing pairs in one room; %zu pairs across the door: %zu surely visible, "
      "%zu surely invisible (%zu of them listed anyway), %zu within %g of the doorway's edge\n",
      n, sameRoomFacing, across, surelyVisible, surelyInvisible, listedInvisible,
      across - surelyVisible - surelyInvisible, kMargin);
  // The construction's verdicts agree with Embree: a sampled pair it calls visible has a free
  // front-to-front segment (among up to 400,000: a corner of a doorway may be a 1e-4 share of
  // the segments), one it calls invisible none among 400.
  const EmbreeScene bvh(scene);
  SplitMix64 rng(5);
  auto freeSegments = [&](uint32_t i, uint32_t j, int tries, bool firstOnly = false) {
    const ConvexPolygon &a = scene.patches[i].polygon, &b = scene.patches[j].polygon;
    int free = 0;
    for (int k = 0; k < tries; ++k) {
      const Vec3 x = uniformPoint(a.vertices, rng), y = uniformPoint(b.vertices, rng);
      if (a.plane.distance(y) > 0 && b.plane.distance(x) > 0 && !bvh.occluded(x, y, i, j)) {
        ++free;
        if (firstOnly) break;
      }
    }
    return free;
  };
  ASSERT_GT(visibleSample.size(), 50u);
  ASSERT_GT(invisibleSample.size(), 50u);
  for (const auto& [i, j] : visibleSample)
    EXPECT_GT(freeSegments(i, j, 400000, true), 0) << i << " " << j;
  for (const auto& [i, j] : invisibleSample) EXPECT_EQ(freeSegments(i, j, 400), 0) << i << " " << j;
  // Conservative: no pair with a free segment left out.
  EXPECT_EQ(missed, 0u) << firstMiss;
  // The check can fail: both kinds occur, and many unlisted pairs are certified invisible.
  EXPECT_GT(surelyVisible, 1000u);
  EXPECT_GT(unlistedInvisible, 1000u);
}

}  // namespace
}  // namespace gv
