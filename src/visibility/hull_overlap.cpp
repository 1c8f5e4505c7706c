// Separating-plane test of a polygon against the convex hull of two polygons (paper §5).
#include "visibility/hull_overlap.h"

#include <algorithm>

namespace gv {
namespace {

/// The range of signed distances of `points` to the plane with normal n through origin o
/// (n need not be unit; distances are in units of |n|).
struct Range {
  double lo = INFINITY, hi = -INFINITY;
};
Range rangeOf(const std::vector<Vec3>& points, const Vec3& n, const Vec3& o) {
  Range r;
  for (const Vec3& p : points) {
    const double d = dot(n, p - o);
    r.lo = std::min(r.lo, d);
    r.hi = std::max(r.hi, d);
  }
  return r;
}

/// True when the plane (n, o) has the hull on one side and b on the other, up to eps·|n|.
bool separates(const Vec3& n, const Vec3& o, const std::vector<Vec3>& hull,
               const std::vector<Vec3>& b, double eps) {
  const double len = length(n);
  if (len == 0) return false;
  const double e = eps * len;
  const Range h = rangeOf(hull, n, o);
  const Range q = rangeOf(b, n, o);
  return (h.hi <= e && q.lo >= -e) || (h.lo >= -e && q.hi <= e);
}

bool boxesMeet(const Aabb& a, const Aabb& b, double eps) {
  return a.lo.x <= b.hi.x + eps && b.lo.x <= a.hi.x + eps && a.lo.y <= b.hi.y + eps &&
         b.lo.y <= a.hi.y + eps && a.lo.z <= b.hi.z + eps && b.lo.z <= a.hi.z + eps;
}

/// Side planes of the hull through an edge of `e` and a vertex of `v`.
bool sidePlaneSeparates(const ConvexPolygon& e, const ConvexPolygon& v, const std::vector<Vec3>& hull,
                        const std::vector<Vec3>& b, double eps) {
  const auto& ev = e.vertices;
  for (size_t i = 0; i < ev.size(); ++i) {
    const Vec3& a = ev[i];
    const Vec3 edge = ev[(i + 1) % ev.size()] - a;
    for (const Vec3& p : v.vertices)
      if (separates(cross(edge, p - a), a, hull, b, eps)) return true;
  }
  return false;
}

}  // namespace

bool meetsConvexHull(const ConvexPolygon& b, const ConvexPolygon& s, const ConvexPolygon& r,
                     const Tolerance& tol) {
  const double eps = tol.length();
  Aabb hullBox = s.bounds();
  hullBox.add(r.bounds());
  if (!boxesMeet(hullBox, b.bounds(), eps)) return false;

  std::vector<Vec3> hull = s.vertices;
  hull.insert(hull.end(), r.vertices.begin(), r.vertices.end());
  const std::vector<Vec3>& bv = b.vertices;
  for (const ConvexPolygon* p : {&b, &s, &r})
    if (separates(p->plane.normal, p->vertices[0], hull, bv, eps)) return false;
  if (sidePlaneSeparates(s, r, hull, bv, eps) || sidePlaneSeparates(r, s, hull, bv, eps)) return false;
  return true;
}

}  // namespace gv
