#include "visibility/single_occluder.h"

#include <vector>

namespace gv {

bool hidesWhole(const ConvexPolygon& blocker, const ConvexPolygon& s, const ConvexPolygon& r,
                double margin) {
  const Plane& plane = blocker.plane;
  const double scale = length(plane.normal);  // distances in length units, whatever the normal
  if (!(scale > 0)) return false;
  const double reach = margin * scale;       // the margin in units of plane.distance
  auto side = [&](const ConvexPolygon& p) {  // +1 / -1 when wholly beyond margin, else 0
    const double first = plane.distance(p.vertices[0]);
    const int sign = first > reach ? 1 : first < -reach ? -1 : 0;
    if (sign == 0) return 0;
    for (size_t k = 1; k < p.vertices.size(); ++k)
      if (sign * plane.distance(p.vertices[k]) <= reach) return 0;
    return sign;
  };
  const int ss = side(s);
  if (ss == 0 || side(r) != -ss) return false;
  // The blocker's edges as inward half-planes in its plane: n × e points inside for a
  // counter-clockwise outline seen from the front.
  const std::vector<Vec3>& b = blocker.vertices;
  const size_t m = b.size();
  for (const Vec3& p : s.vertices) {
    const double dp = plane.distance(p);
    for (const Vec3& q : r.vertices) {
      const double dq = plane.distance(q);
      const Vec3 x = p + (q - p) * (dp / (dp - dq));
      for (size_t i = 0; i < m; ++i) {
        const Vec3 e = b[(i + 1) % m] - b[i];
        const Vec3 inward = cross(plane.normal, e);
        const double len = length(inward);
        if (!(len > 0) || dot(inward, x - b[i]) / len < margin) return false;
      }
    }
  }
  return true;
}

}  // namespace gv
