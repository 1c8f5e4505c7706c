// Joining coplanar portals between the same two cells (see portal_join.h). The hull is CGAL's
// (convex_hull_2 on the plane's 2D coordinates, exact predicates).
#include "visibility/portal_join.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <deque>
#include <iterator>
#include <map>
#include <numeric>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

namespace gv {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// The hull of `a` and `b` (in a's plane) when it is their union: its area exceeds theirs by no
/// more than a band of the length tolerance along its boundary (the pieces' shared edges agree
/// only to rounding).
std::optional<ConvexPolygon> unionIfConvex(const ConvexPolygon& a, const ConvexPolygon& b,
                                           const Tolerance& tol) {
  const Plane& plane = a.plane;
  // (u, v, normal) right-handed: counter-clockwise in (u, v) is counter-clockwise seen from the
  // front.
  const auto [u, v] = perpendicularFrame(plane.normal);
  const Vec3 origin = a.vertices[0];
  std::vector<Kernel::Point_2> points, hull;
  for (const ConvexPolygon* poly : {&a, &b})
    for (const Vec3& w : poly->vertices)
      points.emplace_back(dot(w - origin, u), dot(w - origin, v));
  CGAL::convex_hull_2(points.begin(), points.end(), std::back_inserter(hull));
  std::vector<Vec3> vertices;
  vertices.reserve(hull.size());
  double perimeter = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Kernel::Point_2& p = hull[i];
    const Kernel::Point_2& q = hull[(i + 1) % hull.size()];
    perimeter += std::hypot(q.x() - p.x(), q.y() - p.y());
    vertices.push_back(origin + u * p.x() + v * p.y());
  }
  std::optional<ConvexPolygon> joined = ConvexPolygon::fromVerticesInPlane(vertices, plane, tol);
  if (!joined || joined->area() > a.area() + b.area() + tol.length() * perimeter)
    return std::nullopt;
  return joined;
}

}  // namespace

PortalJoinStats joinCoplanarPortals(Subdivision& sub) {
  const Tolerance tol = sub.tree.tol;
  PortalJoinStats stats;
  stats.portalsBefore = sub.portals.size();
  // Pieces of one opening: same back, same front, same merged plane.
  std::map<std::tuple<uint32_t, uint32_t, int64_t>, std::vector<uint32_t>> groups;
  for (uint32_t i = 0; i < sub.portals.size(); ++i) {
    const Portal& p = sub.portals[i];
    const int64_t plane = p.node >= 0 && static_cast<size_t>(p.node) < sub.tree.nodes.size()
                              ? int64_t{sub.tree.nodes[static_cast<size_t>(p.node)].plane}
                              : -1 - int64_t{i};  // no node: never joined
    groups[{p.back, p.front, plane}].push_back(i);
  }
  std::vector<uint8_t> joinedAway(sub.portals.size(), 0);  // now inside another portal
  std::vector<uint32_t> into(sub.portals.size());          // the portal each was joined into
  std::iota(into.begin(), into.end(), 0u);
  for (auto& [key, ids] : groups) {
    if (ids.size() < 2) continue;
    // A work queue of pieces to try against all the others: a piece that grew goes back on it,
    // so the queue empties only when no two pieces left join (a pair is tried again after either
    // changes). At most pieces + joins scans of the group: quadratic, whatever the input. The
    // joined polygon stays at the lower id (deterministic: ids ascending, queue in order).
    const size_t k = ids.size();
    std::vector<uint8_t> gone(k, 0), queued(k, 1);
    std::vector<Aabb> box(k);
    for (size_t m = 0; m < k; ++m) box[m] = sub.portals[ids[m]].polygon.bounds();
    std::deque<size_t> queue(k);
    std::iota(queue.begin(), queue.end(), size_t{0});
    while (!queue.empty()) {
      size_t i = queue.front();
      queue.pop_front();
      queued[i] = 0;
      if (gone[i]) continue;
      bool grew = false;
      for (size_t j = 0; j < k; ++j) {
        if (j == i || gone[j]) continue;
        // Pieces whose boxes do not touch cannot form a convex union.
        if (!box[i].meets(box[j], tol.length())) continue;
        std::optional<ConvexPolygon> u =
            unionIfConvex(sub.portals[ids[i]].polygon, sub.portals[ids[j]].polygon, tol);
        if (!u) continue;
        const size_t keep = std::min(i, j), drop = std::max(i, j);
        box[keep] = u->bounds();
        sub.portals[ids[keep]].polygon = std::move(*u);
        gone[drop] = 1;
        joinedAway[ids[drop]] = 1;
        into[ids[drop]] = ids[keep];
        i = keep;  // scan on with the grown piece (the rest of j: the others are tried on requeue)
        grew = true;
      }
      if (grew && !queued[i]) {
        queue.push_back(i);
        queued[i] = 1;
      }
    }
  }
  std::vector<Portal> kept;
  std::vector<uint32_t> renumbered(sub.portals.size(), 0);
  for (uint32_t i = 0; i < sub.portals.size(); ++i)
    if (!joinedAway[i]) {
      renumbered[i] = static_cast<uint32_t>(kept.size());
      kept.push_back(std::move(sub.portals[i]));
    }
  // A piece joined into one that was joined on in turn: follow the chain to the portal kept.
  auto newId = [&](uint32_t i) {
    while (into[i] != i) i = into[i];
    return renumbered[i];
  };
  sub.portals = std::move(kept);
  for (Cell& cell : sub.cells) {
    cell.portals.clear();
    // A joined portal spanning two leaves of a merged cell is listed on both: each leaf then
    // sees through a little more than its own piece, which only lets more lines through.
    for (CellPart& part : cell.parts) {
      for (uint32_t& id : part.portals) id = newId(id);
      std::sort(part.portals.begin(), part.portals.end());
      part.portals.erase(std::unique(part.portals.begin(), part.portals.end()), part.portals.end());
    }
  }
  for (uint32_t id = 0; id < sub.portals.size(); ++id) {
    sub.cells[sub.portals[id].back].portals.push_back(id);
    sub.cells[sub.portals[id].front].portals.push_back(id);
  }
  sub.stats.portals = sub.portals.size();
  stats.portalsAfter = sub.portals.size();
  return stats;
}

}  // namespace gv
