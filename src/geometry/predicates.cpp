// Exact orientation predicates through CGAL's filtered exact-predicates kernel. CGAL stays in
// this file only: its headers are slow to compile.
#include "geometry/predicates.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace gv {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_3 toCgal(const Vec3& p) { return {p.x, p.y, p.z}; }

}  // namespace

int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // Four points sharing one coordinate lie in an axis plane: exactly coplanar. Common in
  // architectural scenes, and the case where the filter fails and the exact (slow) path runs.
  if ((a.x == b.x && a.x == c.x && a.x == d.x) || (a.y == b.y && a.y == c.y && a.y == d.y) ||
      (a.z == b.z && a.z == c.z && a.z == d.z))
    return 0;
  // CGAL::orientation(p, q, r, s) is POSITIVE when s is on the positive side of the plane pqr,
  // whose positive side is where (q - p) x (r - p) points: the sign of det[q-p, r-p, s-p].
  return static_cast<int>(CGAL::orientation(toCgal(a), toCgal(b), toCgal(c), toCgal(d)));
}

int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  // CGAL::orientation(p, q, r) in 2D is LEFT_TURN (= POSITIVE) for a counter-clockwise turn.
  return static_cast<int>(
      CGAL::orientation(Kernel::Point_2(ax, ay), Kernel::Point_2(bx, by), Kernel::Point_2(cx, cy)));
}

int orient2dProjected(const Vec3& a, const Vec3& b, const Vec3& c, int dropAxis) {
  const int u = (dropAxis + 1) % 3, v = (dropAxis + 2) % 3;
  return orient2d(a[u], a[v], b[u], b[v], c[u], c[v]);
}

}  // namespace gv
