// Lines of a given direction through a chain of convex portals, by intersecting the portals'
// projections (paper §4.1, witness step). See witness_line.h.
#include "visibility/witness_line.h"

#include <algorithm>
#include <cmath>

namespace gv {
namespace {

// A projected loop is treated as edge-on (no interior to aim at) below this fraction of its
// squared diameter: the exact confirmation would almost surely fail, so it is not worth trying.
constexpr double kEdgeOnArea = 1e-12;

double signedArea2(const std::vector<double>& p) {
  const size_t n = p.size() / 2;
  double s = 0;
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    s += p[2 * i] * p[2 * j + 1] - p[2 * j] * p[2 * i + 1];
  }
  return s;
}

// Keeps the part of `poly` left of the directed line a → b (Sutherland–Hodgman), into `out`.
void clipLeft(const std::vector<double>& poly, double ax, double ay, double bx, double by,
              std::vector<double>& out) {
  out.clear();
  const size_t n = poly.size() / 2;
  const double ex = bx - ax, ey = by - ay;
  auto side = [&](size_t i) { return ex * (poly[2 * i + 1] - ay) - ey * (poly[2 * i] - ax); };
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    const double si = side(i), sj = side(j);
    if (si >= 0) out.insert(out.end(), {poly[2 * i], poly[2 * i + 1]});
    if ((si >= 0) != (sj >= 0)) {
      const double t = si / (si - sj);
      out.push_back(poly[2 * i] + t * (poly[2 * j] - poly[2 * i]));
      out.push_back(poly[2 * i + 1] + t * (poly[2 * j + 1] - poly[2 * i + 1]));
    }
  }
}

}  // namespace

std::optional<Segment> lineAlongDirection(std::span<const std::span<const Vec3>> loops,
                                          const Vec3& d, WitnessScratch& scratch) {
  const double dl = length(d);
  if (loops.empty() || !(dl > 0) || loops[0].empty()) return std::nullopt;
  const Vec3 w = d / dl;
  // An orthonormal frame (u, v) of the plane perpendicular to w.
  const auto [u, v] = perpendicularFrame(w);
  Vec3 origin{};
  for (const Vec3& p : loops[0]) origin += p;
  origin = origin / static_cast<double>(loops[0].size());

  auto project = [&](std::span<const Vec3> loop, std::vector<double>& out) -> bool {
    out.clear();
    double diameter2 = 0;
    for (const Vec3& p : loop) {
      const Vec3 q = p - origin;
      out.push_back(dot(q, u));
      out.push_back(dot(q, v));
      diameter2 = std::max(diameter2, lengthSquared(p - loop[0]));
    }
    const double area2 = signedArea2(out);
    if (!(std::abs(area2) > kEdgeOnArea * diameter2)) return false;
    if (area2 < 0) {
      // Reverse to counter-clockwise.
      const size_t n = out.size() / 2;
      for (size_t i = 0; i < n / 2; ++i) {
        std::swap(out[2 * i], out[2 * (n - 1 - i)]);
        std::swap(out[2 * i + 1], out[2 * (n - 1 - i) + 1]);
      }
    }
    return true;
  };

  std::vector<double> region;  // the common region so far
  if (!project(loops[0], region)) return std::nullopt;
  std::vector<double>& clipper = scratch.a;
  std::vector<double>& tmp = scratch.b;
  for (size_t k = 1; k < loops.size(); ++k) {
    if (!project(loops[k], clipper)) return std::nullopt;
    const size_t n = clipper.size() / 2;
    for (size_t i = 0; i < n && !region.empty(); ++i) {
      const size_t j = (i + 1) % n;
      clipLeft(region, clipper[2 * i], clipper[2 * i + 1], clipper[2 * j], clipper[2 * j + 1], tmp);
      region.swap(tmp);
    }
    if (region.size() < 6) return std::nullopt;
  }
  // Area centroid of the common region (vertex mean when it is a sliver).
  const size_t n = region.size() / 2;
  double cx = 0, cy = 0, a = 0;
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    const double c = region[2 * i] * region[2 * j + 1] - region[2 * j] * region[2 * i + 1];
    a += c;
    cx += (region[2 * i] + region[2 * j]) * c;
    cy += (region[2 * i + 1] + region[2 * j + 1]) * c;
  }
  if (a > 0) {
    cx /= 3 * a, cy /= 3 * a;
  } else {
    cx = cy = 0;
    for (size_t i = 0; i < n; ++i) cx += region[2 * i], cy += region[2 * i + 1];
    cx /= static_cast<double>(n), cy /= static_cast<double>(n);
  }
  const Vec3 p = origin + u * cx + v * cy;
  return Segment{p, p + w};
}

}  // namespace gv
