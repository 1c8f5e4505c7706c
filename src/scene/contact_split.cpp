// Patches cut along the outlines of parallel patches resting on them or hanging just in front.
#include "scene/contact_split.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gv {
namespace {

/// Twice the area over the longest edge: the polygon's narrowest extent, up to a factor 2.
double width(const ConvexPolygon& p) {
  double longest = 0;
  for (size_t i = 0; i < p.vertices.size(); ++i)
    longest = std::max(longest, length(p.vertices[(i + 1) % p.vertices.size()] - p.vertices[i]));
  return longest > 0 ? 2 * p.area() / longest : 0;
}

/// Largest gap at which patch q still shadows a patch (kContactShadowGapRatio).
double maxGap(const ConvexPolygon& q) {
  return kContactShadowGapRatio * std::sqrt(q.area());
}

/// True when q is parallel to p and lies in p's plane or in front of it within maxGap(q).
bool shadows(const ConvexPolygon& q, const ConvexPolygon& p, const Tolerance& tol) {
  if (1 - std::abs(dot(q.normal(), p.normal())) > tol.normalCos()) return false;
  const double gap = maxGap(q);
  for (const Vec3& v : q.vertices) {
    const double d = p.plane.distance(v);
    if (d < -tol.planeOffset() || d > gap + tol.planeOffset()) return false;
  }
  return true;
}

/// The side planes of q's outline seen along p's normal: perpendicular to p through each edge of
/// q projected onto p's plane, each with q's inside at its back.
std::vector<Plane> outlinePlanes(const ConvexPolygon& q, const Plane& onto) {
  std::vector<Vec3> v;
  for (const Vec3& x : q.vertices) v.push_back(x - onto.distance(x) * onto.normal);
  const Vec3 inside = q.centroid() - onto.distance(q.centroid()) * onto.normal;
  std::vector<Plane> planes;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 a = v[i], b = v[(i + 1) % v.size()];
    const Vec3 n = cross(b - a, onto.normal);
    if (length(n) == 0) continue;
    Plane side = Plane::through(a, n);
    if (side.distance(inside) > 0) side = side.flipped();
    planes.push_back(side);
  }
  return planes;
}

/// Cuts `x` along the outline `planes`: the pieces outside the outline, then the one inside.
/// Returns {x} itself when x does not overlap the outline's inside, or when every cut would leave
/// a piece narrower than `minWidth` (such a cut is skipped; the pieces still tile x).
std::vector<ConvexPolygon> cutAlongOutline(const ConvexPolygon& x, const std::vector<Plane>& planes,
                                           double minWidth, const Tolerance& tol) {
  std::vector<ConvexPolygon> pieces;
  ConvexPolygon rest = x;
  for (const Plane& plane : planes) {
    PolygonSplit s = split(rest, plane, tol);
    if (!s.front) continue;   // rest is inside this side
    if (!s.back) return {x};  // rest (so x) is outside the outline
    if (width(*s.front) < minWidth || width(*s.back) < minWidth) continue;
    pieces.push_back(std::move(*s.front));
    rest = std::move(*s.back);
  }
  if (pieces.empty()) return {x};
  pieces.push_back(std::move(rest));
  return pieces;
}

/// Pairs (p, q) with q shadowing p, from a sweep along x over boxes grown by q's gap.
std::vector<std::vector<uint32_t>> shadowingPatches(const Scene& scene, const Tolerance& tol) {
  const size_t n = scene.patches.size();
  std::vector<Aabb> boxes(n);
  for (size_t i = 0; i < n; ++i) {
    const ConvexPolygon& poly = scene.patches[i].polygon;
    boxes[i] = poly.bounds();
    const double grow = maxGap(poly) + tol.planeOffset();
    boxes[i].lo = boxes[i].lo - Vec3{grow, grow, grow};
    boxes[i].hi = boxes[i].hi + Vec3{grow, grow, grow};
  }
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](uint32_t a, uint32_t b) { return boxes[a].lo.x < boxes[b].lo.x; });
  std::vector<std::vector<uint32_t>> shadowsOf(n);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t a = order[i];
    for (size_t j = i + 1; j < n && boxes[order[j]].lo.x <= boxes[a].hi.x; ++j) {
      const uint32_t b = order[j];
      if (boxes[b].lo.y > boxes[a].hi.y || boxes[a].lo.y > boxes[b].hi.y ||
          boxes[b].lo.z > boxes[a].hi.z || boxes[a].lo.z > boxes[b].hi.z)
        continue;
      const ConvexPolygon& pa = scene.patches[a].polygon;
      const ConvexPolygon& pb = scene.patches[b].polygon;
      if (shadows(pb, pa, tol)) shadowsOf[a].push_back(b);
      if (shadows(pa, pb, tol)) shadowsOf[b].push_back(a);
    }
  }
  for (auto& s : shadowsOf) std::sort(s.begin(), s.end());
  return shadowsOf;
}

bool boxesOverlap(const Aabb& a, const Aabb& b, double eps) {
  for (int axis = 0; axis < 3; ++axis)
    if (a.lo[axis] > b.hi[axis] + eps || b.lo[axis] > a.hi[axis] + eps) return false;
  return true;
}

}  // namespace

ContactSplitReport splitPatchesAtContacts(Scene& scene) {
  ContactSplitReport report;
  if (scene.patches.empty()) return report;
  const Tolerance tol = scene.tolerance();
  const double minWidth = kContactMinPieceWidth * tol.scale;
  const std::vector<std::vector<uint32_t>> shadowsOf = shadowingPatches(scene, tol);
  std::vector<Patch> out;
  out.reserve(scene.patches.size());
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const Patch& patch = scene.patches[p];
    std::vector<ConvexPolygon> pieces{patch.polygon};
    for (uint32_t q : shadowsOf[p]) {
      const ConvexPolygon& caster = scene.patches[q].polygon;
      const std::vector<Plane> planes = outlinePlanes(caster, patch.polygon.plane);
      // q's outline projected onto p's plane has q's in-plane extent: its box grown along
      // p's normal by the gap meets every piece q overlaps.
      Aabb reach = caster.bounds();
      const double gap = maxGap(caster) + tol.planeOffset();
      reach.lo = reach.lo - gap * Vec3{1, 1, 1};
      reach.hi = reach.hi + gap * Vec3{1, 1, 1};
      std::vector<ConvexPolygon> next;
      for (ConvexPolygon& x : pieces) {
        if (!boxesOverlap(x.bounds(), reach, tol.length())) {
          next.push_back(std::move(x));
          continue;
        }
        for (ConvexPolygon& y : cutAlongOutline(x, planes, minWidth, tol))
          next.push_back(std::move(y));
      }
      pieces = std::move(next);
    }
    if (pieces.size() > 1) {
      ++report.patchesSplit;
      report.piecesMade += pieces.size();
    }
    for (ConvexPolygon& piece : pieces)
      out.push_back({std::move(piece), patch.material, patch.sourceFace});
  }
  scene.patches = std::move(out);
  scene.report.splitAtContacts += report.patchesSplit;
  scene.report.contactPieces += report.piecesMade;
  return report;
}

}  // namespace gv
