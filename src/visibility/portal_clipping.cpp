// Separating-plane (anti-penumbra) clipping of portals, paper §4.1. See portal_clipping.h for
// the proof that it never removes a point of a stabbing line.
#include "visibility/portal_clipping.h"

#include <cmath>

#include "visibility/separating_plane.h"

namespace gv {
namespace {

// Appends the separators with an edge of `edges` and a vertex of `verts`, oriented to keep the
// pass's side: `keepVertsSide` says whether that is the side of `verts`.
void appendSeparators(std::span<const Vec3> edges, std::span<const Vec3> verts, bool keepVertsSide,
                      std::vector<ClipPlane>& out) {
  ClipPlane plane;
  size_t contact;
  for (size_t i = 0; i < edges.size(); ++i)
    for (size_t j = 0; j < verts.size(); ++j)
      if (exactSeparator(edges, i, verts, j, keepVertsSide, plane, contact)) out.push_back(plane);
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
