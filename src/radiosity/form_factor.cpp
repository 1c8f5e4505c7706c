// Form factors between convex polygons: Lambert's contour integral at a point, adaptive degree-5
// triangle quadrature over the receiver. HSA91 §3.
#include "radiosity/form_factor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "geometry/fast_atan2.h"

namespace gv {
namespace {

/// Radon's 7-point rule for triangles, exact for polynomials of degree 5 (Stroud, "Approximate
/// Calculation of Multiple Integrals", 1971, formula T2:5-1): barycentric points and weights that
/// sum to 1 (the integral is area times the weighted sum).
struct TriangleRule {
  std::array<std::array<double, 3>, 7> points;
  std::array<double, 7> weights;
};

TriangleRule makeRadonRule() {
  const double s = std::sqrt(15.0);
  const double a1 = (6.0 - s) / 21.0, b1 = (9.0 + 2.0 * s) / 21.0, w1 = (155.0 - s) / 1200.0;
  const double a2 = (6.0 + s) / 21.0, b2 = (9.0 - 2.0 * s) / 21.0, w2 = (155.0 + s) / 1200.0;
  TriangleRule r{};
  r.points = {{{1.0 / 3, 1.0 / 3, 1.0 / 3},
               {a1, a1, b1},
               {a1, b1, a1},
               {b1, a1, a1},
               {a2, a2, b2},
               {a2, b2, a2},
               {b2, a2, a2}}};
  r.weights = {9.0 / 40, w1, w1, w1, w2, w2, w2};
  return r;
}

const TriangleRule& radonRule() {
  static const TriangleRule rule = makeRadonRule();
  return rule;
}

/// Below this many "receiver radii" of separation the integrand varies too fast for one 7-point
/// rule per fan triangle and the adaptive check runs. At 4 radii the kernel's variation over the
/// receiver is ~(1/4)^6 beyond degree 5, i.e. ~1e-4 relative: the adaptive tolerance.
constexpr double kFarFieldRatio = 4.0;

struct Triangle {
  Vec3 p0, p1, p2;
  double area() const { return 0.5 * length(cross(p1 - p0, p2 - p0)); }
};

class ReceiverIntegrator {
 public:
  ReceiverIntegrator(const Vec3& normal, std::span<const Vec3> source,
                     const FormFactorOptions& options)
      : normal_(normal), source_(source), options_(options) {}

  /// ∫_T F(dA_x → source) dA_x by the 7-point rule.
  double rule(const Triangle& t) const {
    const TriangleRule& r = radonRule();
    double sum = 0;
    for (size_t k = 0; k < r.points.size(); ++k) {
      const auto& b = r.points[k];
      const Vec3 x = t.p0 * b[0] + t.p1 * b[1] + t.p2 * b[2];
      sum += r.weights[k] * pointToPolygonFormFactor(x, normal_, source_);
    }
    return sum * t.area();
  }

  /// Adaptive refinement of one triangle whose rule value is `coarse`: compare with the four
  /// midpoint children and recurse where they disagree. `budget` is the absolute error allowed.
  double adaptive(const Triangle& t, double coarse, double budget, int depth) const {
    const Vec3 m01 = (t.p0 + t.p1) * 0.5, m12 = (t.p1 + t.p2) * 0.5, m20 = (t.p2 + t.p0) * 0.5;
    const std::array<Triangle, 4> kids{
        {{t.p0, m01, m20}, {m01, t.p1, m12}, {m20, m12, t.p2}, {m01, m12, m20}}};
    std::array<double, 4> values{};
    double fine = 0;
    for (int k = 0; k < 4; ++k) fine += values[k] = rule(kids[k]);
    if (std::abs(fine - coarse) <= budget || depth >= options_.maxDepth) return fine;
    double sum = 0;
    for (int k = 0; k < 4; ++k) sum += adaptive(kids[k], values[k], 0.25 * budget, depth + 1);
    return sum;
  }

 private:
  Vec3 normal_;
  std::span<const Vec3> source_;
  const FormFactorOptions& options_;
};

bool whollyInFront(const ConvexPolygon& p, const Plane& plane, double eps) {
  return std::all_of(p.vertices.begin(), p.vertices.end(),
                     [&](const Vec3& v) { return plane.distance(v) >= -eps; });
}

double radiusAbout(const ConvexPolygon& p, const Vec3& c) {
  double r = 0;
  for (const Vec3& v : p.vertices) r = std::max(r, distance(v, c));
  return r;
}

/// Sample points pulled this fraction towards the centroid: a vertex on an edge the source shares
/// would sit on the source's boundary, where the point form factor is ill-defined.
constexpr double kVertexPull = 0.01;

/// max - min of the point form factor from `receiver` (normal = its plane's) to `source`, over the
/// receiver's pulled vertices, its centroid, and its point nearest to the source's centroid
/// (pulled too); `clipped` adds 0 (a part of the receiver gets none). The nearest point is where
/// the kernel peaks when the source is small and close beside a large receiver (a floor piece
/// along the foot of a wall: from the wall's vertices and centroid the piece looks tiny, from
/// the wall's foot next to it it fills a quarter of the hemisphere), which vertices miss.
double spread(const ConvexPolygon& receiver, const ConvexPolygon& source, bool clipped) {
  const Vec3 c = receiver.centroid();
  const Vec3& n = receiver.plane.normal;
  double lo = pointToPolygonFormFactor(c, n, source.vertices), hi = lo;
  const auto sample = [&](const Vec3& v) {
    const double f = pointToPolygonFormFactor(v + (c - v) * kVertexPull, n, source.vertices);
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  };
  for (const Vec3& v : receiver.vertices) sample(v);
  sample(receiver.nearestPoint(source.centroid()));
  if (clipped) lo = 0;
  return hi - lo;
}

}  // namespace

double pointToPolygonFormFactor(const Vec3& x, const Vec3& n, std::span<const Vec3> vertices) {
  double sum = 0;
  const size_t count = vertices.size();
  if (count == 0) return 0;
  // The innermost loop of every form factor: each vertex's offset is taken once, and the
  // degeneracy test compares squares (no square roots but the one the angle needs).
  const Vec3 first = vertices[0] - x;
  Vec3 u = first;
  for (size_t i = 0; i < count; ++i) {
    const Vec3 w = i + 1 < count ? vertices[i + 1] - x : first;
    const Vec3 c = cross(u, w);
    const double c2 = dot(c, c);
    // x on the edge's line: the edge subtends no solid angle (or x is on the edge itself, a set
    // of measure zero that quadrature points never hit). |c| > 1e-15 |u| |w|, squared.
    if (c2 > 1e-30 * dot(u, u) * dot(w, w)) {
      const double cl = std::sqrt(c2);
      sum += fastAtan2(cl, dot(u, w)) * dot(n, c) / cl;
    }
    u = w;
  }
  return std::min(1.0, std::abs(sum) / (2.0 * std::numbers::pi));
}

double pointFormFactorToFront(const Vec3& x, const Plane& plane, const ConvexPolygon& source,
                              const Tolerance& tol) {
  if (whollyInFront(source, plane, tol.length()))
    return pointToPolygonFormFactor(x, plane.normal, source.vertices);
  const std::optional<ConvexPolygon> front = clipToFront(source, plane, tol);
  return front ? pointToPolygonFormFactor(x, plane.normal, front->vertices) : 0.0;
}

std::optional<ExchangingParts> exchangingParts(const ConvexPolygon& a, const ConvexPolygon& b,
                                               const Tolerance& tol) {
  const double eps = tol.length();
  if (!canFace(a, b, eps)) return std::nullopt;
  ExchangingParts parts{a, b};
  if (!whollyInFront(b, a.plane, eps)) {
    std::optional<ConvexPolygon> front = clipToFront(b, a.plane, tol);
    if (!front) return std::nullopt;
    parts.b = std::move(*front);
  }
  if (!whollyInFront(a, b.plane, eps)) {
    std::optional<ConvexPolygon> front = clipToFront(a, b.plane, tol);
    if (!front) return std::nullopt;
    parts.a = std::move(*front);
  }
  return parts;
}

double formFactor(const ConvexPolygon& a, const ConvexPolygon& b, const Tolerance& tol,
                  const FormFactorOptions& options) {
  return formFactorEstimate(a, b, tol, options).ab;
}

FormFactorEstimate formFactorEstimate(const ConvexPolygon& a, const ConvexPolygon& b,
                                      const Tolerance& tol, const FormFactorOptions& options) {
  const double eps = tol.length();
  if (!canFace(a, b, eps)) return {};
  const double areaA = a.area();
  if (!(areaA > 0)) return {};
  // Only the part of b in front of a's plane is seen from a, and only the part of a in front of
  // b's plane sees b's front: clip each (exactly, not by sampling) before integrating.
  std::optional<ConvexPolygon> clippedA, clippedB;
  const ConvexPolygon* ra = &a;
  const ConvexPolygon* sb = &b;
  if (!whollyInFront(b, a.plane, eps)) {
    clippedB = clipToFront(b, a.plane, tol);
    if (!clippedB) return {};
    sb = &*clippedB;
  }
  if (!whollyInFront(a, b.plane, eps)) {
    clippedA = clipToFront(a, b.plane, tol);
    if (!clippedA) return {};
    ra = &*clippedA;
  }

  const ReceiverIntegrator integrator(a.plane.normal, sb->vertices, options);
  std::vector<Triangle> fan;
  std::vector<double> coarse;
  double total = 0, receiverArea = 0;
  for (size_t k = 1; k + 1 < ra->vertices.size(); ++k) {
    fan.push_back({ra->vertices[0], ra->vertices[k], ra->vertices[k + 1]});
    coarse.push_back(integrator.rule(fan.back()));
    total += coarse.back();
    receiverArea += fan.back().area();
  }
  const Vec3 ca = ra->centroid(), cb = sb->centroid();
  const double ra_ = radiusAbout(*ra, ca), rb = radiusAbout(*sb, cb);
  const bool farField = distance(ca, cb) - ra_ - rb > kFarFieldRatio * ra_;
  if (!farField && receiverArea > 0) {
    double refined = 0;
    for (size_t k = 0; k < fan.size(); ++k) {
      const double budget =
          options.relativeTolerance * std::abs(total) * (fan[k].area() / receiverArea);
      refined += integrator.adaptive(fan[k], coarse[k], budget, 1);
    }
    total = refined;
  }
  FormFactorEstimate e;
  e.ab = std::clamp(total / areaA, 0.0, 1.0);
  e.variationA = spread(*ra, *sb, clippedA.has_value());
  e.variationB = spread(*sb, *ra, clippedB.has_value());
  return e;
}

}  // namespace gv
