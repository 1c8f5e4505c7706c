// Filtered exact Plücker side signs. Paper §6.1.
#include "linespace/filtered_line.h"

#include <cmath>

namespace gv {

FilteredLine FilteredLine::through(const Vec3& a, const Vec3& b) {
  FilteredLine l;
  l.segment = {a, b};
  l.line = PluckerLine::through(a, b);
  const Vec3& d = l.line.direction;
  l.absDirection = {std::abs(d.x), std::abs(d.y), std::abs(d.z)};
  l.absMoment = {std::abs(a.y * b.z) + std::abs(a.z * b.y),
                 std::abs(a.z * b.x) + std::abs(a.x * b.z),
                 std::abs(a.x * b.y) + std::abs(a.y * b.x)};
  return l;
}

int sideSign(const FilteredLine& a, const FilteredLine& b) {
  const double value = side(a.line, b.line);
  const double bound = kPluckerSideErrorFactor *
                       (dot(a.absDirection, b.absMoment) + dot(a.absMoment, b.absDirection));
  if (value > bound) return 1;
  if (value < -bound) return -1;
  return sideExact(a.segment, b.segment);
}

}  // namespace gv
