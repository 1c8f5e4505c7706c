#include "visibility/single_occluder.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gv {

bool hidesWhole(const ConvexPolygon& blocker, const ConvexPolygon& s, const ConvexPolygon& r,
                double margin) {
  const Plane& plane = blocker.plane;
  const double scale = length(plane.normal);  // distances in length units, whatever the normal
  if (!(scale > 0)) return false;
  const std::vector<Vec3>& b = blocker.vertices;
  // A face the importer kept as one polygon may bend off its plane (by up to the planarity
  // tolerance of its diameter): the blocker is then any surface over its outline inside the slab
  // |distance| <= dev. A segment that enters the slab and leaves it inside the outline crosses
  // every such surface (intermediate values), so the crossings are taken with both faces of the
  // slab, and S and R must lie beyond it.
  double dev = 0;
  for (const Vec3& v : b) dev = std::max(dev, std::abs(plane.distance(v)));
  if (!std::isfinite(dev)) return false;
  const double reach = margin * scale + dev;  // in units of plane.distance
  auto side = [&](const ConvexPolygon& p) {   // +1 / -1 when wholly beyond reach, else 0
    const double first = plane.distance(p.vertices[0]);
    const int sign = first > reach ? 1 : first < -reach ? -1 : 0;
    if (sign == 0) return 0;
    for (size_t k = 1; k < p.vertices.size(); ++k)
      if (!(sign * plane.distance(p.vertices[k]) > reach)) return 0;
    return sign;
  };
  const int ss = side(s);
  if (ss == 0 || side(r) != -ss) return false;
  // The blocker's edges as inward half-planes across its plane: n × e points inside for a
  // counter-clockwise outline seen from the front (and is parallel to the plane, so the test
  // reads positions projected onto it).
  const size_t m = b.size();
  for (size_t i = 0; i < m; ++i) {
    const Vec3 inward = cross(plane.normal, b[(i + 1) % m] - b[i]);
    const double len = length(inward);
    if (!(len > 0)) return false;
    for (const Vec3& p : s.vertices)
      for (const Vec3& q : r.vertices)
        for (const double level : {-dev, dev}) {
          const double dp = plane.distance(p) - level, dq = plane.distance(q) - level;
          const Vec3 x = p + (q - p) * (dp / (dp - dq));
          if (!(dot(inward, x - b[i]) >= margin * len)) return false;
        }
  }
  return true;
}

}  // namespace gv
