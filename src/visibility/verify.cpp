// Ray-casting verification of a visibility graph (see verify.h).
#include "visibility/verify.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <unordered_map>

#include "geometry/tolerance.h"
#include "raycast/embree_scene.h"

namespace gv {
namespace {

/// Uniform double in [0, 1) from one raw draw: the same on every standard library.
double unit(std::mt19937_64& rng) {
  return double(rng() >> 11) * 0x1.0p-53;
}

struct PatchSampler {
  std::vector<double> cumulative;  // area prefix sums
  explicit PatchSampler(const Scene& s) {
    double sum = 0;
    for (const Patch& p : s.patches) cumulative.push_back(sum += p.polygon.area());
  }
  uint32_t pick(std::mt19937_64& rng) const {
    const double x = unit(rng) * cumulative.back();
    return uint32_t(std::upper_bound(cumulative.begin(), cumulative.end(), x) - cumulative.begin());
  }
};

Vec3 pointOn(const ConvexPolygon& poly, std::mt19937_64& rng) {
  const auto& v = poly.vertices;
  double total = 0;
  for (size_t k = 1; k + 1 < v.size(); ++k) total += length(cross(v[k] - v[0], v[k + 1] - v[0]));
  double pick = unit(rng) * total;
  size_t k = 1;
  for (; k + 2 < v.size(); ++k) {
    const double a = length(cross(v[k] - v[0], v[k + 1] - v[0]));
    if (pick < a) break;
    pick -= a;
  }
  double a = unit(rng), b = unit(rng);
  if (a + b > 1) a = 1 - a, b = 1 - b;
  return v[0] + (v[k] - v[0]) * a + (v[k + 1] - v[0]) * b;
}

Vec3 cosineDirection(const Vec3& n, std::mt19937_64& rng) {
  const double r = std::sqrt(unit(rng)), phi = 2 * std::numbers::pi * unit(rng);
  const Vec3 t = normalize(std::abs(n.x) < 0.9 ? cross(n, {1, 0, 0}) : cross(n, {0, 1, 0}));
  const Vec3 b = cross(n, t);
  return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
         n * std::sqrt(std::max(0.0, 1 - r * r));
}

/// Where origin + t·d crosses `poly` in double precision, if at a t in [tMin, tMax]. (A crossing
/// point on the polygon's boundary within `eps` counts as crossing.)
std::optional<double> crossingInDouble(const ConvexPolygon& poly, const Vec3& origin, const Vec3& d,
                                       double tMin, double tMax, double eps) {
  const Vec3& n = poly.plane.normal;
  const double den = dot(n, d);
  if (std::abs(den) <= 1e-12 * length(n) * length(d)) return std::nullopt;  // in the plane
  const double t = -poly.plane.distance(origin) / den;
  if (!(t >= tMin && t <= tMax)) return std::nullopt;
  const Vec3 x = origin + d * t;
  const auto& v = poly.vertices;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 e = v[(i + 1) % v.size()] - v[i];
    if (dot(cross(e, x - v[i]), n) < -eps * length(e) * length(n)) return std::nullopt;
  }
  return t;
}

bool crossesInDouble(const ConvexPolygon& poly, const Vec3& origin, const Vec3& d, double tMin,
                     double tMax, double eps) {
  return crossingInDouble(poly, origin, d, tMin, tMax, eps).has_value();
}

/// The first patch other than `a` and `b` that origin + t·d crosses in double precision at a t
/// in [tMin, tMax]: a scan of every patch, for the few hits whose segment ends are in doubt.
std::optional<uint32_t> firstCrossingInDouble(const Scene& scene, const Vec3& origin, const Vec3& d,
                                              double tMin, double tMax, uint32_t a, uint32_t b,
                                              double eps) {
  std::optional<uint32_t> first;
  double best = INFINITY;
  for (size_t k = 0; k < scene.patches.size(); ++k) {
    if (k == a || k == b) continue;
    const auto t = crossingInDouble(scene.patches[k].polygon, origin, d, tMin, tMax, eps);
    if (t && *t < best) best = *t, first = static_cast<uint32_t>(k);
  }
  return first;
}

/// The first patch met by origin + t·d, t in (0, tMax], other than `ignoreA` and `ignoreB`, with
/// Embree's single-precision answers confirmed in double precision: a hit whose patch the ray
/// does not cross in double, or crosses within `contact` of either end (where a start point on
/// an edge shared with another patch leaves float rounding to decide), is skipped and the ray
/// cast again past it. After a few skips the hit is taken as it is (verification stays strict).
std::optional<RayHit> confirmedFirstHit(const EmbreeScene& rays, const Scene& scene,
                                        const Vec3& origin, const Vec3& d, double tMax,
                                        uint32_t ignoreA, uint32_t ignoreB, double contact,
                                        double eps) {
  constexpr int kMaxSkips = 8;
  const double len = length(d);
  const double tContact = len > 0 ? contact / len : 0;
  double base = 0;  // parameter of the current cast's origin
  uint32_t ignore = ignoreA;
  for (int k = 0;; ++k) {
    const Vec3 o = origin + d * base;
    const auto hit = rays.firstHit(o, d, tMax - base, ignore);
    if (!hit) return std::nullopt;
    const double t = base + hit->t;
    const bool own = hit->patch == ignoreA || hit->patch == ignoreB;
    if (!own && (k == kMaxSkips || crossesInDouble(scene.patches[hit->patch].polygon, origin, d,
                                                   tContact, tMax - tContact, eps)))
      return RayHit{hit->patch, t};
    if (k == kMaxSkips) return std::nullopt;  // only the pair's own patches, in contact
    base = t;
    ignore = hit->patch;
  }
}

/// Faces in contact at the model tolerance: facing each other from one plane (every vertex of
/// one within the tolerance of the other's plane, normals opposite within a loose angle, as a
/// wall's foot on a floor, each a little out of true). A gap between them is below the scene's
/// resolution (geometry/tolerance.h): a ray crossing it is not a sightline of the contract.
bool inContact(const ConvexPolygon& a, const ConvexPolygon& b, double tolerance) {
  constexpr double kContactCos = 0.9999995;  // 1e-3 rad
  if (!(dot(a.normal(), b.normal()) <= -kContactCos)) return false;
  auto near = [tolerance](const ConvexPolygon& of, const ConvexPolygon& plane) {
    for (const Vec3& v : of.vertices)
      if (!(std::abs(plane.plane.distance(v)) <= tolerance)) return false;
    return true;
  };
  return near(a, b) || near(b, a);
}

}  // namespace

VerifyReport verifyVisibility(const Scene& scene, const VisibilityGraph& graph,
                              const VerifyOptions& options) {
  VerifyReport report;
  const size_t n = scene.patches.size();
  std::unordered_map<uint64_t, const Interaction*> listed;
  for (const Interaction& in : graph.interactions) {
    if (in.r >= n) {
      ++report.invalidPairs;
      continue;
    }
    listed[(uint64_t(in.s) << 32) | in.r] = &in;
  }
  if (n == 0) return report;
  const EmbreeScene rays(scene);
  const PatchSampler sampler(scene);
  std::mt19937_64 rng(options.seed);
  const double eps = 1e-9 * scene.bounds().diagonal();
  // Embree intersects in single precision: hits closer than this to a ray's origin are contact.
  const double offset = kVerifyContactDistance * scene.bounds().diagonal();
  const double rayContact =
      std::max(options.rayContact, kVerifyContactDistance) * scene.bounds().diagonal();
  // The model tolerance (geometry/tolerance.h), restated here: faces closer than this are one.
  const double contactTolerance = kRelativeModelEpsilon * scene.bounds().diagonal();

  for (uint64_t i = 0; i < options.rays; ++i) {
    const uint32_t s = sampler.pick(rng);
    const ConvexPolygon& sp = scene.patches[s].polygon;
    const Vec3 o = pointOn(sp, rng);
    const Vec3 d = cosineDirection(sp.normal(), rng);
    ++report.rays;
    // Start just in front of S: a patch overlapping S in its own plane (a box resting on a floor)
    // meets the ray at distance 0, which is contact, not sight.
    const auto hit = confirmedFirstHit(rays, scene, o + sp.normal() * offset, d, INFINITY, s, s,
                                       rayContact, eps);
    if (!hit || dot(d, scene.patches[hit->patch].polygon.normal()) >= 0) continue;
    ++report.raysHittingFront;
    if (inContact(sp, scene.patches[hit->patch].polygon, contactTolerance)) {
      ++report.contactRays;
      continue;
    }
    const uint32_t a = std::min(s, hit->patch), b = std::max(s, hit->patch);
    if (!listed.count((uint64_t(a) << 32) | b)) {
      if (report.examples.size() < kVerifyExamples)
        report.examples.push_back(
            fmt::format("pair ({}, {}) not listed: ray from ({}, {}, {}) along "
                        "({}, {}, {}) meets {} first",
                        a, b, o.x, o.y, o.z, d.x, d.y, d.z, hit->patch));
      ++report.missingPairs;
    }
  }

  // Unlisted pairs, drawn uniformly: up to kUnlistedSegments front-to-front segments each.
  for (uint64_t i = 0; i < options.unlistedPairs; ++i) {
    const uint32_t s = uint32_t(rng() % n), r = uint32_t(rng() % n);
    if (s == r) continue;
    const uint32_t a = std::min(s, r), b = std::max(s, r);
    if (listed.count((uint64_t(a) << 32) | b)) continue;
    ++report.unlistedDrawn;
    const ConvexPolygon& sp = scene.patches[s].polygon;
    const ConvexPolygon& rp = scene.patches[r].polygon;
    if (inContact(sp, rp, contactTolerance)) continue;
    bool tried = false, throughCrack = false, missing = false;
    for (int k = 0; k < kUnlistedSegments && !missing; ++k) {
      const Vec3 p = pointOn(sp, rng), q = pointOn(rp, rng);
      if (sp.plane.distance(q) <= eps || rp.plane.distance(p) <= eps) continue;
      tried = true;
      const Vec3 p1 = p + sp.normal() * offset, q1 = q + rp.normal() * offset;
      if (rays.occluded(p1, q1, s, r)) continue;
      // Free in single precision; in double, nothing may cross the segment between its ends'
      // contact distances (a crossing within `eps` of a patch's edge counts).
      const double tContact = offset / std::max(length(q - p), offset);
      if (firstCrossingInDouble(scene, p, q - p, tContact, 1 - tContact, s, r, eps)) continue;
      // Free only through a gap narrower than the contact distance beside a patch's edge (two
      // faces meeting at a corner, their vertices 1e-6 apart): closed by the tolerance policy,
      // counted apart.
      if (firstCrossingInDouble(scene, p, q - p, tContact, 1 - tContact, s, r, offset)) {
        throughCrack = true;
        continue;
      }
      if (report.examples.size() < kVerifyExamples)
        report.examples.push_back(fmt::format(
            "pair ({}, {}) not listed: segment ({}, {}, {}) to ({}, {}, {}) meets nothing", a, b,
            p.x, p.y, p.z, q.x, q.y, q.z));
      missing = true;
    }
    report.unlistedTried += tried;
    report.missingUnlisted += missing;
    report.unlistedThroughCracks += throughCrack && !missing;
  }

  if (graph.interactions.empty()) return report;
  // Tightness: a segment is free when the offset segment meets nothing (Embree) or what it
  // meets the segment between the sampled points does not cross (as above).
  for (uint64_t i = 0; i < options.tightnessPairs; ++i) {
    const Interaction& in = graph.interactions[rng() % graph.interactions.size()];
    if (in.r >= n) continue;
    const ConvexPolygon& sp = scene.patches[in.s].polygon;
    const ConvexPolygon& rp = scene.patches[in.r].polygon;
    bool free = false;
    int tried = 0;
    for (int k = 0; k < kTightnessSegments * 4 && tried < kTightnessSegments && !free; ++k) {
      const Vec3 p = pointOn(sp, rng), q = pointOn(rp, rng);
      if (sp.plane.distance(q) <= eps || rp.plane.distance(p) <= eps) continue;
      ++tried;
      const Vec3 p1 = p + sp.normal() * offset, q1 = q + rp.normal() * offset;
      if (!rays.occluded(p1, q1, in.s, in.r)) {
        free = true;
        break;
      }
      const auto first = confirmedFirstHit(rays, scene, p1, q1 - p1, 1.0, in.s, in.r, offset, eps);
      const double tContact = offset / std::max(length(q - p), offset);
      if (!first || !crossesInDouble(scene.patches[first->patch].polygon, p, q - p, tContact,
                                     1 - tContact, eps))
        free = true;
    }
    if (tried == 0) continue;  // no front-to-front segment found: not a pair rays can judge
    ++report.tightnessPairs;
    if (!free) ++report.excess;
  }
  for (uint64_t i = 0; i < options.segments; ++i) {
    const Interaction& in = graph.interactions[rng() % graph.interactions.size()];
    if (in.r >= n) continue;
    const ConvexPolygon& sp = scene.patches[in.s].polygon;
    const ConvexPolygon& rp = scene.patches[in.r].polygon;
    const Vec3 p = pointOn(sp, rng), q = pointOn(rp, rng);
    if (sp.plane.distance(q) <= eps || rp.plane.distance(p) <= eps) continue;  // not front to front
    ++report.segments;
    const Vec3 p1 = p + sp.normal() * offset, q1 = q + rp.normal() * offset;
    if (!rays.occluded(p1, q1, in.s, in.r)) continue;
    // Embree's "occluded" confirmed in double: some patch other than S and R really crossed.
    const auto first = confirmedFirstHit(rays, scene, p1, q1 - p1, 1.0, in.s, in.r, offset, eps);
    if (!first) continue;
    // The contract speaks of the segment p-q itself; p1-q1 runs up to `offset` beside it, and
    // where S, R and another patch are nearly coplanar (a wall modelled in pieces a little out of
    // line) it can meet that patch while p-q does not: such a hit is not one of the contract's.
    const double tContact = offset / std::max(length(q - p), offset);
    auto crossesPQ = [&](uint32_t patch) {
      return crossesInDouble(scene.patches[patch].polygon, p, q - p, tContact, 1 - tContact, eps);
    };
    if (!crossesPQ(first->patch)) {
      ++report.offsetOnlyHits;
      continue;
    }
    ++report.blockedSegments;
    if (in.blockers.empty()) {
      if (report.examples.size() < kVerifyExamples)
        report.examples.push_back(
            fmt::format("VISIBLE pair ({}, {}) has a blocked segment ({}, {}, "
                        "{}) to ({}, {}, {})",
                        in.s, in.r, p.x, p.y, p.z, q.x, q.y, q.z));
      ++report.blockedVisible;
      continue;
    }
    auto isBlocker = [&](uint32_t patch) {
      return std::binary_search(in.blockers.begin(), in.blockers.end(), patch);
    };
    const double tExact = eps / std::max(length(q - p), eps);
    for (const auto& [from, to, start, end] :
         {std::tuple{p1, q1, p, q}, std::tuple{q1, p1, q, p}}) {
      const auto hit =
          confirmedFirstHit(rays, scene, from, to - from, 1.0, in.s, in.r, offset, eps);
      if (!hit || isBlocker(hit->patch)) continue;
      if (!crossesPQ(hit->patch)) {
        ++report.offsetOnlyHits;
        continue;
      }
      // The segment itself may meet another patch first, closer to its end than the offset:
      // one lying on S or R within that distance (a solid's face resting on a wall piece that
      // is a little out of line). The contract's first hit is that one.
      const auto exact =
          firstCrossingInDouble(scene, start, end - start, tExact, 1 - tExact, in.s, in.r, eps);
      if (exact && *exact != hit->patch && isBlocker(*exact)) {
        ++report.contactFirstHits;
        continue;
      }
      const uint32_t missing = exact ? *exact : hit->patch;
      if (report.examples.size() < kVerifyExamples)
        report.examples.push_back(
            fmt::format("patch {} is met first on segment ({}, {}, {}) to "
                        "({}, {}, {}) of pair ({}, {}) but is not a blocker",
                        missing, start.x, start.y, start.z, end.x, end.y, end.z, in.s, in.r));
      ++report.missingBlockers;
    }
  }
  return report;
}

}  // namespace gv
