// Separating-plane (anti-penumbra) clipping of portals, paper §4.1. See portal_clipping.h for
// the proof that it never removes a point of a stabbing line.
#include "visibility/portal_clipping.h"

#include <cmath>

#include "geometry/predicates.h"

namespace gv {
namespace {

// Sign of det[b - a, v - a, q - a] = dot(n, q - a) with n = (b - a) x (v - a) precomputed, exact:
// a floating-point evaluation is trusted when it exceeds Shewchuk's error bound for this very
// expression ((7 + 56 eps) eps times the permanent, here rounded up to 1e-14), otherwise the exact
// predicate decides.
struct PlaneThrough3 {
  Vec3 a, b, v, n, nAbs;

  PlaneThrough3(const Vec3& a_, const Vec3& b_, const Vec3& v_) : a(a_), b(b_), v(v_) {
    const Vec3 e = b - a, w = v - a;
    n = cross(e, w);
    nAbs = {std::abs(e.y * w.z) + std::abs(e.z * w.y), std::abs(e.z * w.x) + std::abs(e.x * w.z),
            std::abs(e.x * w.y) + std::abs(e.y * w.x)};
  }
  int sign(const Vec3& q) const {
    const Vec3 d = q - a;
    const double det = dot(n, d);
    const double permanent =
        nAbs.x * std::abs(d.x) + nAbs.y * std::abs(d.y) + nAbs.z * std::abs(d.z);
    if (det > 1e-14 * permanent) return 1;
    if (det < -1e-14 * permanent) return -1;
    return orient3d(a, b, v, q);
  }
};

// Is the plane through edges[i], edges[i+1] and verts[j] a separator, and on which side are the
// edge's polygon's other vertices (the returned sign, 0 when it is not a separator)? Exact.
// Required for the proof in portal_clipping.h: each polygon on its closed side, and the two
// polygons meeting the plane in disjoint sets. The edge's polygon may touch the plane only along
// the edge; the vertex's polygon may touch it at the vertex or along one more vertex (an edge
// parallel to the plane: the usual case in axis-aligned levels), and then the two contact
// segments must be disjoint, decided by exact 2D orientations in the plane.
int separatorSide(const PlaneThrough3& plane, std::span<const Vec3> edges, size_t i,
                  std::span<const Vec3> verts, size_t j) {
  const size_t ne = edges.size(), nv = verts.size();
  // The first vertex of the edge's polygon off the edge sets the side; the vertex's polygon is
  // tested next (it rejects most candidates), the rest of the edge's polygon last. The conditions
  // are the same in any order.
  const size_t k0 = (i + 2) % ne;
  if (k0 == i) return 0;  // fewer than 3 vertices
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
    const Vec3 &a = plane.a, &b = plane.b, &v = plane.v, &w = verts[other];
    const int ov = orient2dProjected(a, b, v, axis), ow = orient2dProjected(a, b, w, axis);
    const int oa = orient2dProjected(v, w, a, axis), ob = orient2dProjected(v, w, b, axis);
    const bool disjoint = (ov != 0 && ov == ow) || (oa != 0 && oa == ob);
    if (!disjoint) return 0;
  }
  for (size_t k = 0; k < ne; ++k) {
    if (k == i || k == (i + 1) % ne || k == k0) continue;
    if (plane.sign(edges[k]) != sigma) return 0;
  }
  return sigma;
}

// Appends the separators with an edge of `edges` and a vertex of `verts`, oriented to keep the
// pass's side: `keepVertsSide` says whether that is the side of `verts`.
void appendSeparators(std::span<const Vec3> edges, std::span<const Vec3> verts, bool keepVertsSide,
                      std::vector<ClipPlane>& out) {
  const size_t ne = edges.size(), nv = verts.size();
  for (size_t i = 0; i < ne; ++i) {
    const Vec3& a = edges[i];
    const Vec3& b = edges[(i + 1) % ne];
    for (size_t j = 0; j < nv; ++j) {
      const PlaneThrough3 plane(a, b, verts[j]);
      const int sigma = separatorSide(plane, edges, i, verts, j);
      if (sigma == 0) continue;
      const double lenN = length(plane.n);
      // A nearly collinear (edge, vertex) pair spans a badly conditioned plane: its rounded
      // normal could tilt by more than the clip slack covers, so it is not used (keeping more).
      if (!(lenN > kRelativeModelEpsilon * length(b - a) * length(verts[j] - a))) continue;
      // Keep the pass's side: the side of `verts` (-sigma) or of `edges` (+sigma).
      const double keep = keepVertsSide ? -sigma : sigma;
      const Vec3 u = plane.n * (keep / lenN);
      out.push_back({u, dot(u, a)});
    }
  }
}

}  // namespace

void clipToHalfspace(std::span<const Vec3> in, const Vec3& unitNormal, double offset, double slack,
                     Winding& out) {
  out.clear();
  const size_t n = in.size();
  if (n == 0) return;
  const double limit = offset - slack;  // keep dot(u, x) >= limit
  bool allIn = true, allOut = true;
  for (const Vec3& p : in) {
    const bool inside = dot(unitNormal, p) >= limit;
    allIn = allIn && inside;
    allOut = allOut && !inside;
  }
  if (allIn) {
    out.assign(in.begin(), in.end());
    return;
  }
  if (allOut) return;
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = in[i];
    const Vec3& q = in[(i + 1) % n];
    const double dp = dot(unitNormal, p) - limit, dq = dot(unitNormal, q) - limit;
    if (dp >= 0) out.push_back(p);
    if ((dp >= 0) != (dq >= 0)) {
      const double t = dp / (dp - dq);
      out.push_back(p + (q - p) * t);
    }
  }
}

void separatingPlanes(std::span<const Vec3> source, std::span<const Vec3> pass,
                      std::vector<ClipPlane>& out) {
  out.clear();
  if (source.size() < 3 || pass.size() < 3) return;
  // Edge of the source, vertex of the pass: keep the pass's (vertex) side.
  appendSeparators(source, pass, true, out);
  // Edge of the pass, vertex of the source: keep the pass's (edge) side.
  appendSeparators(pass, source, false, out);
}

bool clipByPlanes(std::span<const ClipPlane> planes, Winding& target, Winding& scratch,
                  const Tolerance& tol) {
  for (const ClipPlane& p : planes) {
    if (target.empty()) return false;
    clipToHalfspace(target, p.unitNormal, p.offset, tol.length(), scratch);
    target.swap(scratch);
  }
  return !target.empty();
}

bool clipBySeparatingPlanes(std::span<const Vec3> source, std::span<const Vec3> pass,
                            Winding& target, const Tolerance& tol) {
  std::vector<ClipPlane> planes;
  separatingPlanes(source, pass, planes);
  Winding scratch;
  scratch.reserve(target.size() + 8);
  return clipByPlanes(planes, target, scratch, tol);
}

Vec3 newellNormal(std::span<const Vec3> loop) {
  Vec3 n{};
  const size_t k = loop.size();
  if (k < 3) return n;
  const Vec3 o = loop[0];  // relative to a vertex: less cancellation far from the origin
  for (size_t i = 0; i < k; ++i) n += cross(loop[i] - o, loop[(i + 1) % k] - o);
  return n;
}

}  // namespace gv
