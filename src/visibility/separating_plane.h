// The exact test of a candidate separating plane (paper §4.1, Fig. 5): is the plane through an
// edge of one portal and a vertex of the other a separator of the two, and which way does it
// keep? One test for both searches that list the planes, the exhaustive one of
// portal_clipping.cpp and the extreme-vertex one of separator_search.cpp; portal_clipping.h has
// the proof that clipping by such planes never removes a point of a stabbing line.
// Header-only: it runs on the stabbing search's hottest path.
#pragma once

#include <cmath>
#include <cstddef>
#include <span>

#include "geometry/predicates.h"
#include "geometry/tolerance.h"
#include "geometry/vec3.h"
#include "visibility/portal_clipping.h"

namespace gv {

/// i + 1 modulo n, without an integer division (n >= 1, i < n).
inline size_t nextIndex(size_t i, size_t n) {
  return i + 1 == n ? 0 : i + 1;
}

/// Sign of det[b - a, v - a, q - a], exact: the floating-point value is trusted beyond
/// Shewchuk's error bound for this expression ((7 + 56 eps) eps times the permanent, rounded up
/// to 1e-14), else orient3d decides. Holds its points by address (they outlive it): no copies on
/// this hot path.
struct PlaneThrough3 {
  const Vec3 *a, *b, *v;
  Vec3 n, nAbs;
  double nn;  // |n|^2

  PlaneThrough3(const Vec3& a_, const Vec3& b_, const Vec3& v_) : a(&a_), b(&b_), v(&v_) {
    const Vec3 e = b_ - a_, w = v_ - a_;
    n = cross(e, w);
    nn = lengthSquared(n);
    nAbs = {std::abs(e.y * w.z) + std::abs(e.z * w.y), std::abs(e.z * w.x) + std::abs(e.x * w.z),
            std::abs(e.x * w.y) + std::abs(e.y * w.x)};
  }
  int sign(const Vec3& q) const {
    const Vec3 d = q - *a;
    const double det = dot(n, d);
    const double permanent =
        nAbs.x * std::abs(d.x) + nAbs.y * std::abs(d.y) + nAbs.z * std::abs(d.z);
    if (det > 1e-14 * permanent) return 1;
    if (det < -1e-14 * permanent) return -1;
    // A vertex shared by the two portals (common in real maps) is exactly on the plane: no need
    // for the exact arithmetic to say so.
    if (q == *a || q == *b || q == *v) return 0;
    return orient3d(*a, *b, *v, q);
  }
};

/// orient2dProjected with a floating-point filter first (Shewchuk's bound for orient2d, rounded
/// up): the exact predicate runs only when the rounded determinant is too small to trust.
inline int orient2dFast(const Vec3& a, const Vec3& b, const Vec3& c, int dropAxis) {
  const int u = (dropAxis + 1) % 3, v = (dropAxis + 2) % 3;
  const double l = (b[u] - a[u]) * (c[v] - a[v]), r = (b[v] - a[v]) * (c[u] - a[u]);
  const double det = l - r, bound = 4e-16 * (std::abs(l) + std::abs(r));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return orient2dProjected(a, b, c, dropAxis);
}

/// Is the plane through edges[i], edges[i+1] and verts[j] a separator, and on which side are the
/// edge polygon's other vertices (the returned sign, 0 when it is not a separator)? Exact.
/// Required for the proof in portal_clipping.h: each polygon on its closed side, and the two
/// polygons meeting the plane in disjoint sets. The edge's polygon may touch the plane only along
/// the edge; the vertex's polygon may touch it at the vertex or along one more vertex (an edge
/// parallel to the plane: the usual case in axis-aligned levels), and then the two contact
/// segments must be disjoint, decided by exact 2D orientations in the plane. `contact` receives
/// that second vertex (verts.size() when there is none).
inline int separatorSide(const PlaneThrough3& plane, std::span<const Vec3> edges, size_t i,
                         std::span<const Vec3> verts, size_t j, size_t& contact) {
  const size_t ne = edges.size(), nv = verts.size();
  if (ne < 3) return 0;
  // The first vertex of the edge's polygon off the edge sets the side; the vertex's polygon is
  // tested next (it rejects most candidates), the rest of the edge's polygon last. The
  // conditions are the same in any order.
  const size_t i1 = nextIndex(i, ne), k0 = nextIndex(i1, ne);
  const int sigma = plane.sign(edges[k0]);
  if (sigma == 0) return 0;
  size_t other = nv;  // a second vertex of `verts` on the plane, if any
  for (size_t k = 0; k < nv; ++k) {
    if (k == j) continue;
    const int s = plane.sign(verts[k]);
    if (s == sigma) return 0;
    if (s == 0) {
      if (other != nv) return 0;
      other = k;
    }
  }
  if (other != nv) {
    // Contact segments [a, b] and [v, w]: disjoint if v and w are strictly on one side of line
    // ab, or a and b strictly on one side of line vw (collinear cases are rejected).
    const int axis = dominantAxis(plane.n);
    const Vec3 &a = *plane.a, &b = *plane.b, &v = *plane.v, &w = verts[other];
    const int ov = orient2dFast(a, b, v, axis), ow = orient2dFast(a, b, w, axis);
    const int oa = orient2dFast(v, w, a, axis), ob = orient2dFast(v, w, b, axis);
    const bool disjoint = (ov != 0 && ov == ow) || (oa != 0 && oa == ob);
    if (!disjoint) return 0;
  }
  for (size_t k = 0; k < ne; ++k) {
    if (k == i || k == i1 || k == k0) continue;
    if (plane.sign(edges[k]) != sigma) return 0;
  }
  contact = other;
  return sigma;
}

/// The separator through edge i of `edges` (and the next vertex) and vertex j of `verts`, if it
/// is one, oriented to keep the pass's side: the side of `verts` when `keepVertsSide`, else of
/// `edges`. False when it is not a separator, or when the (edge, vertex) pair is nearly collinear:
/// such a plane is badly conditioned, its rounded normal could tilt by more than the clip slack
/// covers, so it is not used (keeping more). `contact` as in separatorSide.
inline bool exactSeparator(std::span<const Vec3> edges, size_t i, std::span<const Vec3> verts,
                           size_t j, bool keepVertsSide, ClipPlane& out, size_t& contact) {
  const Vec3& a = edges[i];
  const Vec3& b = edges[nextIndex(i, edges.size())];
  const PlaneThrough3 plane(a, b, verts[j]);
  constexpr double kMinSine2 = kRelativeModelEpsilon * kRelativeModelEpsilon;
  if (!(plane.nn > kMinSine2 * lengthSquared(b - a) * lengthSquared(verts[j] - a))) return false;
  contact = verts.size();
  const int sigma = separatorSide(plane, edges, i, verts, j, contact);
  if (sigma == 0) return false;
  // Keep the pass's side: the side of `verts` (-sigma) or of `edges` (+sigma).
  const double keep = keepVertsSide ? -sigma : sigma;
  const Vec3 u = plane.n * (keep / std::sqrt(plane.nn));
  out = {u, dot(u, a)};
  return true;
}

}  // namespace gv
