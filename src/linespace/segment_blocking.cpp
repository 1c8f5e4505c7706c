// Sample segments against a blocker list by plane and Plücker side tests. Paper §6.3.
#include "linespace/segment_blocking.h"

#include <cmath>

namespace gv {

namespace {

/// Is x (on b's plane) inside b's closed polygon?
bool insidePolygon(const Vec3& x, const BlockerGeometry& b) {
  const size_t n = b.vertices.size();
  for (size_t k = 0; k < n; ++k)
    if (dot(cross(b.vertices[(k + 1) % n] - b.vertices[k], x - b.vertices[k]), b.plane.normal) < 0)
      return false;
  return true;
}

}  // namespace

bool segmentMeets(const Vec3& p, const Vec3& q, const PluckerLine& line, const BlockerGeometry& b,
                  double contact) {
  const double dp = b.plane.distance(p), dq = b.plane.distance(q);
  if (std::abs(dp) <= contact) return insidePolygon(p, b);
  if (std::abs(dq) <= contact) return insidePolygon(q, b);
  if (!((dp > 0 && dq < 0) || (dp < 0 && dq > 0))) return false;
  bool positive = false, negative = false;
  for (const FilteredLine& e : b.edges) {
    const double s = side(line, e.line);
    positive |= s > 0;
    negative |= s < 0;
    if (positive && negative) return false;
  }
  return true;
}

bool segmentBlocked(const Vec3& p, const Vec3& q, std::span<const uint32_t> blockers,
                    const BlockerTable& table, double contact) {
  const PluckerLine line = PluckerLine::through(p, q);
  for (const uint32_t id : blockers)
    if (segmentMeets(p, q, line, table[id], contact)) return true;
  return false;
}

}  // namespace gv
