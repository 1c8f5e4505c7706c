// Sample segments against a blocker list by plane and Plücker side tests. Paper §6.3.
#include "linespace/segment_blocking.h"

namespace gv {

bool segmentMeets(const Vec3& p, const Vec3& q, const PluckerLine& line, const BlockerGeometry& b) {
  const double dp = b.plane.distance(p), dq = b.plane.distance(q);
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
                    const BlockerTable& table) {
  const PluckerLine line = PluckerLine::through(p, q);
  for (const uint32_t id : blockers)
    if (segmentMeets(p, q, line, table[id])) return true;
  return false;
}

}  // namespace gv
