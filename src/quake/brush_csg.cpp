// Brush solids from 3-point planes, and the part of a face another convex solid leaves visible
// (one Sutherland–Hodgman pass per half-space of the other solid, the outside pieces kept).
#include "quake/brush_csg.h"

#include <algorithm>
#include <cmath>

namespace gv {

Plane PlaneSnapper::snap(const Plane& plane, const Vec3& centre, double radius) {
  // Canonical orientation: the largest normal component positive, the first of near-equal ones
  // (within a band far wider than the normals of two planes that merge differ by), so that both
  // orientations of one plane, and of nearly the same plane, agree.
  Vec3 n = plane.normal;
  double d = plane.offset;
  const double largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
  int axis = 0;
  while (std::abs(n[axis]) < largest - 1e-3) ++axis;
  const bool flip = n[axis] < 0;
  if (flip) {
    n = -n;
    d = -d;
  }
  // Planes this close differ in normal by at most planeOffset / radius (~1e-3 for a small brush):
  // they share a key at this quantum unless a rounding boundary falls between them, and such a
  // pair is simply not merged (the unsnapped status quo).
  const double quantum = 1e-2;
  const std::array<int64_t, 3> key{static_cast<int64_t>(std::llround(n.x / quantum)),
                                   static_cast<int64_t>(std::llround(n.y / quantum)),
                                   static_cast<int64_t>(std::llround(n.z / quantum))};
  std::vector<Plane>& reps = buckets_[key];
  for (const Plane& r : reps) {
    // Largest gap between the two planes over the ball (centre, radius).
    const Vec3 dn = r.normal - n;
    const double gap = std::abs(dot(dn, centre) - (r.offset - d)) + length(dn) * radius;
    if (gap <= tol_.planeOffset()) return flip ? r.flipped() : r;
  }
  reps.push_back({n, d});
  return plane;
}

std::optional<BrushSolid> brushSolid(const MapBrush& brush, const Tolerance& tol,
                                     PlaneSnapper* snapper) {
  if (brush.sides.size() < 4) return std::nullopt;
  std::vector<Plane> planes;
  planes.reserve(brush.sides.size());
  for (const MapBrushSide& s : brush.sides) {
    const Vec3 a = s.points[0] - s.points[1], b = s.points[2] - s.points[1];
    const Vec3 n = s.outwardNormal();
    // |a × b| / max(|a|, |b|) bounds the distance of a point from the line of the other two.
    if (length(n) <= tol.length() * std::max(length(a), length(b))) return std::nullopt;
    planes.push_back(Plane::through(s.points[1], n));
  }
  std::optional<ConvexPolyhedron> shape = ConvexPolyhedron::fromHalfspaces(planes, tol);
  if (!shape) return std::nullopt;
  if (snapper) {  // snap over the brush's actual extent, then rebuild
    const Aabb box = shape->bounds();
    for (Plane& h : planes) h = snapper->snap(h, box.center(), 0.5 * box.diagonal());
    shape = ConvexPolyhedron::fromHalfspaces(planes, tol);
    if (!shape) return std::nullopt;
  }
  BrushSolid solid;
  solid.faceSide.reserve(shape->faces.size());
  for (const PolyhedronFace& f : shape->faces) {
    // fromHalfspaces merges duplicates and drops redundant planes: find the (first) side whose
    // plane this face lies on.
    const Plane& h = shape->halfspaces[f.halfspace];
    int best = 0;
    double bestScore = -INFINITY;
    for (size_t i = 0; i < planes.size(); ++i) {
      const double score =
          dot(planes[i].normal, h.normal) - std::abs(planes[i].offset - h.offset) / tol.scale;
      if (score > bestScore + 1e-15) {
        bestScore = score;
        best = static_cast<int>(i);
      }
    }
    solid.faceSide.push_back(best);
  }
  solid.box = shape->bounds();
  solid.shape = std::move(*shape);
  return solid;
}

std::vector<ConvexPolygon> visibleParts(const ConvexPolygon& face, const ConvexPolyhedron& other,
                                        const CoplanarRule& rule, const Tolerance& tol) {
  const double on = rule.onTolerance;
  if (rule.flatAgainstOnly) {
    const bool flatAgainst =
        std::any_of(other.halfspaces.begin(), other.halfspaces.end(), [&](const Plane& h) {
          if (dot(face.plane.normal, h.normal) >= 0) return false;
          return std::all_of(face.vertices.begin(), face.vertices.end(),
                             [&](const Vec3& v) { return std::abs(h.distance(v)) <= on; });
        });
    if (!flatAgainst) return {face};
  }
  std::vector<ConvexPolygon> outside;
  ConvexPolygon remaining = face;  // the part still possibly inside `other`
  for (const Plane& h : other.halfspaces) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3& v : remaining.vertices) {
      const double d = h.distance(v);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    if (lo >= -on && hi <= on) {  // in h's plane: on the boundary of `other`
      const bool opposite = dot(remaining.plane.normal, h.normal) < 0;
      if (opposite || rule.otherWinsTies) continue;  // hidden there if inside the other planes
      return {face};
    }
    if (lo >= -on) return {face};  // outside `other` (touching at most): nothing hidden
    // Inside h: decided by the other planes. Only within the length tolerance, not `on`: a face
    // reaching out of `other` by less than `on` must keep that strip, or a crack opens.
    if (hi <= tol.length()) continue;
    PolygonSplit pieces = split(remaining, h, tol);
    if (!pieces.back) return {face};  // what would be hidden is a sliver
    if (pieces.front) outside.push_back(std::move(*pieces.front));
    remaining = std::move(*pieces.back);
  }
  return outside;  // `remaining` is inside (or hidden on the boundary of) `other`
}

}  // namespace gv
