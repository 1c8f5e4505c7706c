#include "visibility/single_occluder.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gv {

OccluderSlab occluderSlab(const ConvexPolygon& blocker) {
  OccluderSlab slab;
  slab.scale = length(blocker.plane.normal);  // distances in length units, whatever the normal
  // A face the importer kept as one polygon may bend off its plane (by up to the planarity
  // tolerance of its diameter): the blocker is then any surface over its outline inside the slab
  // |distance| <= dev. A segment that enters the slab and leaves it inside the outline crosses
  // every such surface (intermediate values), so the crossings are taken with both faces of the
  // slab, and S and R must lie beyond it.
  for (const Vec3& v : blocker.vertices)
    slab.dev = std::max(slab.dev, std::abs(blocker.plane.distance(v)));
  if (!(slab.scale > 0) || !std::isfinite(slab.dev)) slab.usable = false;
  return slab;
}

int sideOfSlab(const ConvexPolygon& blocker, const OccluderSlab& slab, const ConvexPolygon& p,
               double margin) {
  if (!slab.usable) return 0;
  const Plane& plane = blocker.plane;
  const double reach = margin * slab.scale + slab.dev;  // in units of plane.distance
  const double first = plane.distance(p.vertices[0]);
  const int sign = first > reach ? 1 : first < -reach ? -1 : 0;
  if (sign == 0) return 0;
  for (size_t k = 1; k < p.vertices.size(); ++k)
    if (!(sign * plane.distance(p.vertices[k]) > reach)) return 0;
  return sign;
}

bool inwardEdges(const ConvexPolygon& blocker, std::span<InwardEdge> out) {
  const std::vector<Vec3>& b = blocker.vertices;
  const size_t m = b.size();
  bool usable = true;
  for (size_t i = 0; i < m; ++i) {
    out[i].inward = cross(blocker.plane.normal, b[(i + 1) % m] - b[i]);
    out[i].length = length(out[i].inward);
    usable = usable && out[i].length > 0;
  }
  return usable;
}

bool crossesInside(const ConvexPolygon& blocker, const OccluderSlab& slab,
                   std::span<const InwardEdge> edges, const ConvexPolygon& s,
                   const ConvexPolygon& r, double margin) {
  const Plane& plane = blocker.plane;
  const std::vector<Vec3>& b = blocker.vertices;
  const double dev = slab.dev;
  const size_t m = b.size();
  // Each crossing point is tested against every edge: a blocker that fails, as most do, fails at
  // the first crossing point outside it.
  auto inside = [&](const Vec3& x) {
    for (size_t i = 0; i < m; ++i)
      if (!(dot(edges[i].inward, x - b[i]) >= margin * edges[i].length)) return false;
    return true;
  };
  // Where the segments between the vertices cross the slab's two faces: conv(S ∪ R) meets each
  // face in the convex hull of these points.
  for (const Vec3& p : s.vertices)
    for (const Vec3& q : r.vertices)
      for (const double level : {-dev, dev}) {
        const double dp = plane.distance(p) - level, dq = plane.distance(q) - level;
        if (!inside(p + (q - p) * (dp / (dp - dq)))) return false;
      }
  return true;
}

bool crossesInside(const ConvexPolygon& blocker, const OccluderSlab& slab, const ConvexPolygon& s,
                   const ConvexPolygon& r, double margin) {
  // The blocker's edges prepared on the stack for the usual few, on the heap past that.
  constexpr size_t kEdges = 16;
  const size_t m = blocker.vertices.size();
  InwardEdge local[kEdges];
  std::vector<InwardEdge> heap;
  std::span<InwardEdge> edges(local, std::min(m, kEdges));
  if (m > kEdges) {
    heap.resize(m);
    edges = heap;
  }
  if (!inwardEdges(blocker, edges)) return false;
  return crossesInside(blocker, slab, edges, s, r, margin);
}

bool hidesWhole(const ConvexPolygon& blocker, const ConvexPolygon& s, const ConvexPolygon& r,
                double margin) {
  const OccluderSlab slab = occluderSlab(blocker);
  const int ss = sideOfSlab(blocker, slab, s, margin);
  return ss != 0 && sideOfSlab(blocker, slab, r, margin) == -ss &&
         crossesInside(blocker, slab, s, r, margin);
}

}  // namespace gv
