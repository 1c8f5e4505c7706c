// Exact orientation predicates through CGAL's filtered exact-predicates kernel. CGAL stays in
// this file only: its headers are slow to compile.
#include "geometry/predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>

namespace gv {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_3 toCgal(const Vec3& p) {
  return {p.x, p.y, p.z};
}

}  // namespace

namespace {

// Exactly coplanar quadruples that coordinate comparisons alone reveal: all four in one axis plane,
// or two lines through them both parallel to one axis (parallel lines are coplanar). These are
// the common degeneracies of architectural scenes (vertical door edges, axis-aligned walls) and
// exactly the inputs on which the floating-point filter fails and the slow exact path would run.
bool axisCoplanar(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  for (int k = 0; k < 3; ++k)
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k]) return true;
  auto alongAxis = [](const Vec3& p, const Vec3& q, int k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    return p[u] == q[u] && p[v] == q[v];
  };
  for (int k = 0; k < 3; ++k) {
    if ((alongAxis(a, b, k) && alongAxis(c, d, k)) || (alongAxis(a, c, k) && alongAxis(b, d, k)) ||
        (alongAxis(a, d, k) && alongAxis(b, c, k)))
      return true;
  }
  return false;
}

// Integers below 2^15 in magnitude: then differences need 17 bits, 2x2 minors 34 and the 3x3
// determinant 52, so its floating-point evaluation is exact (Quake portal files and many clipped
// windings have such coordinates; it spares the exact arithmetic on their many coplanar cases).
constexpr double kExactIntegerBound = 32768;
bool smallInteger(double x) {
  return std::abs(x) < kExactIntegerBound && std::trunc(x) == x;
}
bool smallIntegers(const Vec3& p) {
  return smallInteger(p.x) && smallInteger(p.y) && smallInteger(p.z);
}

}  // namespace

int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  if (axisCoplanar(a, b, c, d)) return 0;
  if (smallIntegers(a) && smallIntegers(b) && smallIntegers(c) && smallIntegers(d)) {
    const Vec3 e = b - a, f = c - a, g = d - a;
    const double det = e.x * (f.y * g.z - f.z * g.y) - e.y * (f.x * g.z - f.z * g.x) +
                       e.z * (f.x * g.y - f.y * g.x);
    return (det > 0) - (det < 0);
  }
  // CGAL::orientation(p, q, r, s) is POSITIVE when s is on the positive side of the plane pqr,
  // whose positive side is where (q - p) x (r - p) points: the sign of det[q-p, r-p, s-p].
  return static_cast<int>(CGAL::orientation(toCgal(a), toCgal(b), toCgal(c), toCgal(d)));
}

int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  // Three points on one axis-parallel line (common in axis-aligned levels) are collinear.
  if ((ax == bx && ax == cx) || (ay == by && ay == cy)) return 0;
  if (smallInteger(ax) && smallInteger(ay) && smallInteger(bx) && smallInteger(by) &&
      smallInteger(cx) && smallInteger(cy)) {
    // Exact: differences need 17 bits, the products 34.
    const double det = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    return (det > 0) - (det < 0);
  }
  // CGAL::orientation(p, q, r) in 2D is LEFT_TURN (= POSITIVE) for a counter-clockwise turn.
  return static_cast<int>(
      CGAL::orientation(Kernel::Point_2(ax, ay), Kernel::Point_2(bx, by), Kernel::Point_2(cx, cy)));
}

int orient2dProjected(const Vec3& a, const Vec3& b, const Vec3& c, int dropAxis) {
  const int u = (dropAxis + 1) % 3, v = (dropAxis + 2) % 3;
  return orient2d(a[u], a[v], b[u], b[v], c[u], c[v]);
}

}  // namespace gv
