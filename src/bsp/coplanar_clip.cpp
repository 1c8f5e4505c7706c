// Convex intersection and difference within a plane by clipping with edge planes. Paper §3.
#include "bsp/coplanar_clip.h"

#include <utility>

namespace gv {

std::vector<Plane> edgePlanes(const ConvexPolygon& polygon) {
  const std::vector<Vec3>& v = polygon.vertices;
  std::vector<Plane> planes;
  planes.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 edge = v[(i + 1) % v.size()] - v[i];
    // cross(normal, edge) points into a counter-clockwise polygon. The polygon's invariant
    // (edges longer than the length tolerance) keeps it non-zero.
    planes.push_back(Plane::through(v[i], cross(polygon.plane.normal, edge)));
  }
  return planes;
}

std::optional<ConvexPolygon> intersectCoplanar(const ConvexPolygon& a, const ConvexPolygon& b,
                                               const Tolerance& tol) {
  // Edge planes do not depend on b's facing: reversing b reverses its vertices and its normal,
  // so cross(normal, edge) is unchanged.
  std::optional<ConvexPolygon> piece = a;
  for (const Plane& e : edgePlanes(b)) {
    piece = clipToFront(*piece, e, tol);
    if (!piece) return std::nullopt;
  }
  return piece;
}

bool subtractCoplanar(const ConvexPolygon& a, const ConvexPolygon& b, const Tolerance& tol,
                      std::vector<ConvexPolygon>& out) {
  // Peel off, edge by edge of b, the part of `a` outside that edge; what remains is inside b.
  ConvexPolygon rest = a;
  bool cut = false;
  for (const Plane& e : edgePlanes(b)) {
    PolygonSplit s = split(rest, e, tol);
    // `rest` is a sliver along b's edge, or wholly outside this edge: what is left of `a` is
    // outside b (keeping the sliver is the conservative choice: more portal, never less).
    if (s.on || (!s.front && s.back)) {
      out.push_back(std::move(rest));
      return cut;
    }
    if (!s.front) return true;  // cut into two slivers, both dropped
    if (s.back) {
      out.push_back(std::move(*s.back));
      cut = true;
    }
    rest = std::move(*s.front);
  }
  return true;  // `rest` lies inside b and is removed
}

}  // namespace gv
