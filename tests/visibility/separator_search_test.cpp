// Tests of the fast separating-plane search (paper §4.1): on seeded random portal pairs (general
// position and axis-aligned integer ones, where vertices tie exactly) it finds the same planes as
// the exhaustive search over every (edge, vertex) pair, and every plane separates the two
// polygons.
#include "visibility/separator_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "visibility/portal_clipping.h"

namespace gv {
namespace {

// A convex n-gon around `centre` in the plane spanned by u, v (counter-clockwise about u x v),
// optionally snapped to integers (then ties and exact coplanarity are common).
Winding polygon(std::mt19937& rng, const Vec3& centre, const Vec3& u, const Vec3& v, int n,
                double radius, bool snap) {
  std::uniform_real_distribution<double> jitter(0.0, 0.6);
  Winding w;
  for (int k = 0; k < n; ++k) {
    const double a = (k + jitter(rng)) * 2 * std::numbers::pi / n;
    Vec3 p = centre + u * (radius * std::cos(a)) + v * (radius * std::sin(a));
    if (snap) p = {std::round(p.x), std::round(p.y), std::round(p.z)};
    if (!w.empty() && p == w.back()) continue;
    w.push_back(p);
  }
  if (w.size() > 1 && w.front() == w.back()) w.pop_back();
  return w;
}

std::string describe(const Winding& w) {
  std::string out;
  for (const Vec3& p : w)
    out += "(" + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + ") ";
  return out;
}

bool samePlane(const ClipPlane& a, const ClipPlane& b) {
  return length(a.unitNormal - b.unitNormal) < 1e-9 && std::abs(a.offset - b.offset) < 1e-7;
}

bool contains(const std::vector<ClipPlane>& set, const ClipPlane& p) {
  for (const ClipPlane& q : set)
    if (samePlane(p, q)) return true;
  return false;
}

void expectSameAsExhaustive(const Winding& s, const Winding& p, int& planesSeen) {
  std::vector<ClipPlane> slow, fast;
  separatingPlanes(s, p, slow);
  findSeparatingPlanes(s, p, fast);
  for (const ClipPlane& q : slow)
    EXPECT_TRUE(contains(fast, q)) << "missed a plane " << q.unitNormal.x << " " << q.unitNormal.y
                                   << " " << q.unitNormal.z << " " << q.offset << "\n"
                                   << describe(s) << "\n"
                                   << describe(p);
  for (const ClipPlane& q : fast) {
    EXPECT_TRUE(contains(slow, q)) << "a plane the exhaustive search rejects";
    // Keeps the pass's side, has the source on the other (closed) side.
    for (const Vec3& x : p) EXPECT_GE(dot(q.unitNormal, x) - q.offset, -1e-9);
    for (const Vec3& x : s) EXPECT_LE(dot(q.unitNormal, x) - q.offset, 1e-9);
  }
  planesSeen += static_cast<int>(slow.size());
}

TEST(SeparatorSearch, MatchesExhaustiveSearchOnRandomPortalPairs) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> sides(3, 8);
  int planes = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 n = normalize(Vec3{unit(rng), unit(rng), unit(rng)} + Vec3{0, 0, 1.5});
    const Vec3 u = normalize(cross(n, Vec3{0.3, 1, 0.1})), v = cross(n, u);
    const Vec3 c0{unit(rng), unit(rng), 0}, c1{unit(rng) * 2, unit(rng) * 2, 1 + unit(rng) * 0.9};
    const Winding s = polygon(rng, c0, u, v, sides(rng), 0.3 + 0.7 * (unit(rng) + 1), false);
    const Winding p = polygon(rng, c1, u, v, sides(rng), 0.3 + 0.7 * (unit(rng) + 1), false);
    expectSameAsExhaustive(s, p, planes);
  }
  EXPECT_GT(planes, 3000);
}

TEST(SeparatorSearch, MatchesExhaustiveSearchOnAxisAlignedIntegerPortals) {
  // Quake-like: portals in axis planes with integer vertices; many vertex ties and coplanar
  // contacts (an edge of the pass parallel to an edge of the source).
  std::mt19937 rng(777);
  std::uniform_int_distribution<int> coord(-8, 8), size(1, 6), axisPick(0, 2), sides(3, 6);
  int planes = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    auto axisPortal = [&](int axis, double offset) {
      Vec3 c{double(coord(rng)), double(coord(rng)), double(coord(rng))};
      c[axis] = offset;
      Vec3 u{}, v{};
      u[(axis + 1) % 3] = 1, v[(axis + 2) % 3] = 1;
      return polygon(rng, c, u, v, sides(rng), size(rng) * 1.5, true);
    };
    const int a0 = axisPick(rng), a1 = axisPick(rng);
    const Winding s = axisPortal(a0, 0);
    const Winding p = axisPortal(a1, a1 == a0 ? size(rng) * 2.0 : 9.0);
    if (s.size() < 3 || p.size() < 3) continue;
    expectSameAsExhaustive(s, p, planes);
  }
  EXPECT_GT(planes, 3000);
}

TEST(SeparatorSearch, TwoAlignedSquaresHaveTheFourAntipenumbraPlanes) {
  // Unit squares at z = 0 and z = 1, one above the other: each of the 4 source edges has one
  // separator (through the opposite pass edge, e.g. z = y). Each holds an edge of both squares;
  // the exhaustive search lists it 4 times (2 vertices x 2 families), the fast one once.
  const Winding s{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Winding p{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::vector<ClipPlane> fast;
  findSeparatingPlanes(s, p, fast);
  EXPECT_EQ(fast.size(), 4u);
  int planes = 0;
  expectSameAsExhaustive(s, p, planes);
}

}  // namespace
}  // namespace gv
