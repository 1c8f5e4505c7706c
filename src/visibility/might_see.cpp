// Flooding the adjacency graph from each directed portal under the two plane tests (see header).
#include "visibility/might_see.h"

#include <algorithm>

namespace gv {
namespace {

/// max over `points` of dot(n, x - o)
double maxAlong(const std::vector<Vec3>& points, const Vec3& n, const Vec3& o) {
  double m = -INFINITY;
  for (const Vec3& p : points) m = std::max(m, dot(n, p - o));
  return m;
}

}  // namespace

MightSee::MightSee(const Subdivision& sub, const Tolerance& tol, size_t maxCells)
    : all_(sub.cells.size(), true) {
  if (sub.cells.size() > maxCells) return;
  const double eps = tol.planeOffset();  // generous: a looser set only prunes less
  sets_.resize(2 * sub.portals.size());
  std::vector<uint32_t> queue;
  for (uint32_t pid = 0; pid < sub.portals.size(); ++pid) {
    const Portal& p = sub.portals[pid];
    for (const bool intoFront : {false, true}) {
      const uint32_t first = intoFront ? p.front : p.back;
      const Vec3 np = intoFront ? p.polygon.normal() : -p.polygon.normal();
      const Vec3 op = p.polygon.vertices[0];
      CellSet reach(sub.cells.size());
      reach.insert(first);
      queue.assign(1, first);
      while (!queue.empty()) {
        const uint32_t cell = queue.back();
        queue.pop_back();
        for (uint32_t qid : sub.cells[cell].portals) {
          if (qid == pid) continue;
          const Portal& q = sub.portals[qid];
          const uint32_t next = q.other(cell);
          if (reach.contains(next)) continue;
          const Vec3 nq = q.front == next ? q.polygon.normal() : -q.polygon.normal();
          // Q has a point not behind P; P has a point not in front of Q.
          if (maxAlong(q.polygon.vertices, np, op) <= -eps) continue;
          if (-maxAlong(p.polygon.vertices, -nq, q.polygon.vertices[0]) >= eps) continue;
          reach.insert(next);
          queue.push_back(next);
        }
      }
      sets_[2 * pid + (intoFront ? 1 : 0)] = std::move(reach);
    }
  }
}

}  // namespace gv
