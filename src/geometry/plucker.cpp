// Exact Plücker side of two lines given by end points. Paper §4.1.
#include "geometry/plucker.h"

#include "geometry/predicates.h"

namespace gv {

int sideExact(const Segment& l, const Segment& e) {
  // det[q-p, r-p, s-p] is the permuted inner product of line(p→q) and line(r→s): both are the
  // 4x4 determinant of the homogeneous points (p,1), (q,1), (r,1), (s,1) up to the same sign.
  return orient3d(l.a, l.b, e.a, e.b);
}

}  // namespace gv
