// Separating-plane test of a polygon against the convex hull of two polygons (paper §5).
#include "visibility/hull_overlap.h"

#include <algorithm>
#include <cmath>

namespace gv {
namespace {

/// The range of signed distances of `points` to the plane with normal n through origin o
/// (n need not be unit; distances are in units of |n|).
struct Range {
  double lo = INFINITY, hi = -INFINITY;
};
Range rangeOf(std::span<const Vec3> points, const Vec3& n, const Vec3& o) {
  Range r;
  for (const Vec3& p : points) {
    const double d = dot(n, p - o);
    r.lo = std::min(r.lo, d);
    r.hi = std::max(r.hi, d);
  }
  return r;
}

/// Unit normals closer than this in every coordinate (and offsets within the length tolerance)
/// are one plane: rounding in the cross products of nearby vertices is ~1e-15 of the scene.
constexpr double kRepeatedNormal = 1e-9;

}  // namespace

void PairHull::addPlane(const Vec3& n, double c, double touch) {
  for (size_t i = 0; i < c_.size(); ++i)
    if (std::abs(nx_[i] - n.x) <= kRepeatedNormal && std::abs(ny_[i] - n.y) <= kRepeatedNormal &&
        std::abs(nz_[i] - n.z) <= kRepeatedNormal && std::abs(c_[i] - c) <= eps_) {
      touch_[i] = std::max(touch_[i], touch);  // the stricter separation of the two
      return;
    }
  nx_.push_back(n.x);
  ny_.push_back(n.y);
  nz_.push_back(n.z);
  c_.push_back(c);
  touch_.push_back(touch);
}

void PairHull::consider(const Vec3& n, const Vec3& o) {
  const double len = length(n);
  if (!(len > 0)) return;
  const Vec3 u = n * (1 / len);
  // Most candidate planes cut through the hull: stop as soon as points lie beyond the tolerance
  // on both sides (neither orientation is kept), before the range is complete.
  Range h;
  for (const Vec3& p : hull_) {
    const double d = dot(u, p - o);
    h.lo = std::min(h.lo, d);
    h.hi = std::max(h.hi, d);
    if (h.lo < -eps_ && h.hi > eps_) return;
  }
  const double c = dot(u, o);
  const double touch = !shaft_ && h.hi - h.lo < kFlatHull * eps_ ? eps_ : -eps_;
  if (h.hi <= eps_) addPlane(u, c, touch);     // hull behind: separates what lies in front
  if (h.lo >= -eps_) addPlane(-u, -c, touch);  // hull in front: separates what lies behind
}

PairHull::PairHull(const ConvexPolygon& s, const ConvexPolygon& r, const Tolerance& tol)
    : eps_(tol.length()) {
  box_ = s.bounds();
  box_.add(r.bounds());
  hull_ = s.vertices;
  hull_.insert(hull_.end(), r.vertices.begin(), r.vertices.end());
  consider(s.plane.normal, s.vertices[0]);
  consider(r.plane.normal, r.vertices[0]);
  // Side planes through an edge of one polygon and a vertex of the other.
  for (const auto& [e, v] : {std::pair{&s, &r}, std::pair{&r, &s}}) {
    const auto& ev = e->vertices;
    for (size_t i = 0; i < ev.size(); ++i) {
      const Vec3& a = ev[i];
      const Vec3 edge = ev[(i + 1) % ev.size()] - a;
      for (const Vec3& p : v->vertices) consider(cross(edge, p - a), a);
    }
  }
}

PairHull::PairHull(const ConvexPolygon& s, const Aabb& around, const Tolerance& tol)
    : eps_(tol.length()), shaft_(true) {
  box_ = s.bounds();
  box_.add(around);
  hull_ = s.vertices;
  Vec3 corners[8];
  for (int k = 0; k < 8; ++k)
    corners[k] = {(k & 1) ? around.hi.x : around.lo.x, (k & 2) ? around.hi.y : around.lo.y,
                  (k & 4) ? around.hi.z : around.lo.z};
  hull_.insert(hull_.end(), corners, corners + 8);
  consider(s.plane.normal, s.vertices[0]);
  // Side planes through an edge of s and a corner, and through an edge of the box and a vertex
  // of s. Any subset of the hull's supporting planes would do: a missing one only separates less.
  const auto& sv = s.vertices;
  for (size_t i = 0; i < sv.size(); ++i) {
    const Vec3 edge = sv[(i + 1) % sv.size()] - sv[i];
    for (const Vec3& c : corners) consider(cross(edge, c - sv[i]), sv[i]);
  }
  for (int k = 0; k < 8; ++k)
    for (int axis = 0; axis < 3; ++axis) {
      if (k & (1 << axis)) continue;  // each edge once, from its low corner
      const Vec3 edge = corners[k | (1 << axis)] - corners[k];
      for (const Vec3& v : sv) consider(cross(edge, v - corners[k]), corners[k]);
    }
}

bool PairHull::boxMeets(const Aabb& bBox) const {
  return box_.meets(bBox, eps_);
}

bool PairHull::separatesBox(const Aabb& box) const {
  // The least n·x − c over the box, per plane, at the corner the normal points away from. For a
  // pair, half the tolerance of margin beyond the plane's touch: a vertex v in the box then has
  // n·v − c >= touch + eps / 2 less rounding (~1e-16 of the scene), well above meetsInBox's
  // touch, so that plane separates its polygon. For a shaft, see shaft_.
  for (size_t i = 0; i < c_.size(); ++i) {
    const double least = (nx_[i] >= 0 ? nx_[i] * box.lo.x : nx_[i] * box.hi.x) +
                         (ny_[i] >= 0 ? ny_[i] * box.lo.y : ny_[i] * box.hi.y) +
                         (nz_[i] >= 0 ? nz_[i] * box.lo.z : nz_[i] * box.hi.z) - c_[i];
    if (least >= (shaft_ ? 3 * eps_ : touch_[i] + 0.5 * eps_)) return true;
  }
  return false;
}

size_t PairHull::keepUnseparated(uint32_t* ids, size_t n, std::span<const Aabb> boxes) const {
  // separatesBox's arithmetic, term for term, so that the answers are the same.
  for (size_t i = 0; i < c_.size() && n > 0; ++i) {
    const double nx = nx_[i], ny = ny_[i], nz = nz_[i], c = c_[i];
    const double beyond = shaft_ ? 3 * eps_ : touch_[i] + 0.5 * eps_;
    const bool px = nx >= 0, py = ny >= 0, pz = nz >= 0;
    size_t kept = 0;
    for (size_t k = 0; k < n; ++k) {
      const uint32_t id = ids[k];
      const Aabb& box = boxes[id];
      const double least = (px ? nx * box.lo.x : nx * box.hi.x) +
                           (py ? ny * box.lo.y : ny * box.hi.y) +
                           (pz ? nz * box.lo.z : nz * box.hi.z) - c;
      ids[kept] = id;
      kept += !(least >= beyond);
    }
    n = kept;
  }
  return n;
}

bool PairHull::meets(const ConvexPolygon& b, const Aabb& bBox) const {
  return box_.meets(bBox, eps_) && meetsInBox(b);
}

bool PairHull::meetsInBox(std::span<const Vec3> bv, const Vec3& n, double len) const {
  // The hull's side planes first: they are prepared, and most separations are found there.
  // `deep`: b's first vertex lies more than twice the tolerance inside every side plane. The
  // side planes are all the hull's facets (s's and r's planes, and the planes through an edge of
  // one and a vertex of the other: a facet with two vertices of one polygon holds an edge of it
  // or is its plane), so a ball of radius 2 eps about that vertex lies in the hull, which then
  // reaches beyond b's plane on both sides by more than the tolerance: b's own plane cannot
  // separate either, and b meets the hull.
  const size_t planes = c_.size();
  const Vec3& v0 = bv[0];
  bool deep = true;
  for (size_t i = 0; i < planes; ++i) {
    const double d0 = nx_[i] * v0.x + ny_[i] * v0.y + nz_[i] * v0.z - c_[i];
    if (d0 < touch_[i]) {
      deep = deep && d0 < -2 * eps_;
      continue;
    }
    deep = false;
    bool separates = true;  // every vertex of b at or beyond the plane (within eps, or +eps)
    for (size_t k = 1; k < bv.size(); ++k) {
      const Vec3& v = bv[k];
      if (nx_[i] * v.x + ny_[i] * v.y + nz_[i] * v.z - c_[i] < touch_[i]) {
        separates = false;
        break;
      }
    }
    if (separates) return false;
  }
  if (deep && planes > 0) return true;
  // b's own plane: separated when the hull lies on one side of it (within e) and b on it.
  if (!(len > 0)) return true;
  const double e = eps_ * len;
  const Range q = rangeOf(bv, n, bv[0]);
  bool behind = q.lo >= -e;  // still possible: hull at or behind (h.hi <= e), b at or in front
  bool ahead = q.hi <= e;    // still possible: hull at or ahead (h.lo >= -e), b at or behind
  for (const Vec3& h : hull_) {
    if (!behind && !ahead) return true;  // the hull straddles b's plane
    const double d = dot(n, h - bv[0]);
    if (d > e) behind = false;
    if (d < -e) ahead = false;
  }
  return !behind && !ahead;
}

bool meetsConvexHull(const ConvexPolygon& b, const ConvexPolygon& s, const ConvexPolygon& r,
                     const Tolerance& tol) {
  return PairHull(s, r, tol).meets(b);
}

}  // namespace gv
