// Fast separating-plane search for two convex portals (paper §4.1). See separator_search.h; the
// exact acceptance test is the one of portal_clipping.cpp (whose proof covers these planes).
#include "visibility/separator_search.h"

#include <cmath>

#include "geometry/predicates.h"
#include "geometry/tolerance.h"

namespace gv {
namespace {

// A vertex whose sine of angle to the edge's line (squared) is below this is taken as on it.
constexpr double kAxisVertex = 1e-20;
// A point whose sine of angle to a candidate plane (squared) exceeds this is clearly on its side
// (far beyond rounding): the candidate is decided without the exact test.
constexpr double kClearSide = 1e-12;

// i + 1 modulo n, without an integer division (n >= 1, i < n).
inline size_t nextIndex(size_t i, size_t n) {
  return i + 1 == n ? 0 : i + 1;
}

// Sign of det[b - a, v - a, q - a], exact: the floating-point value is trusted beyond Shewchuk's
// error bound for this expression (rounded up to 1e-14 x the permanent), else orient3d decides.
// Holds its points by address (they outlive it): no copies on this hot path.
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

// orient2dProjected with a floating-point filter first (Shewchuk's bound for orient2d, rounded
// up): the exact predicate runs only when the rounded determinant is too small to trust.
int orient2dFast(const Vec3& a, const Vec3& b, const Vec3& c, int dropAxis) {
  const int u = (dropAxis + 1) % 3, v = (dropAxis + 2) % 3;
  const double l = (b[u] - a[u]) * (c[v] - a[v]), r = (b[v] - a[v]) * (c[u] - a[u]);
  const double det = l - r, bound = 4e-16 * (std::abs(l) + std::abs(r));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return orient2dProjected(a, b, c, dropAxis);
}

// The exact separator test of portal_clipping.cpp: is the plane through edges[i], edges[i+1] and
// verts[j] a separator, and on which side are the edge polygon's other vertices (0: not one)?
// Each polygon on its closed side; the edge's polygon touching the plane only along the edge;
// the vertex's polygon at the vertex or along one more vertex, the two contact segments disjoint.
// `contact` receives that second vertex (verts.size() when there is none).
int separatorSide(const PlaneThrough3& plane, std::span<const Vec3> edges, size_t i,
                  std::span<const Vec3> verts, size_t j, size_t& contact) {
  const size_t ne = edges.size(), nv = verts.size();
  if (ne < 3) return 0;
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

// `secondFamily`: edges of the pass, vertices of the source. A plane touching the source along
// an edge of it holds an edge of each polygon, and the first family (edges of the source) has
// listed it already under the same conditions: it is not listed twice.
void acceptIfSeparator(std::span<const Vec3> edges, size_t i, std::span<const Vec3> verts, size_t j,
                       bool keepVertsSide, bool secondFamily, std::vector<ClipPlane>& out) {
  const Vec3& a = edges[i];
  const Vec3& b = edges[nextIndex(i, edges.size())];
  const PlaneThrough3 plane(a, b, verts[j]);
  // A nearly collinear (edge, vertex) pair spans a badly conditioned plane: its rounded normal
  // could tilt by more than the clip slack covers, so it is not used (keeping more).
  constexpr double kMinSine2 = kRelativeModelEpsilon * kRelativeModelEpsilon;
  if (!(plane.nn > kMinSine2 * lengthSquared(b - a) * lengthSquared(verts[j] - a))) return;
  const size_t nv = verts.size();
  size_t contact = nv;
  const int sigma = separatorSide(plane, edges, i, verts, j, contact);
  if (sigma == 0) return;
  if (secondFamily && contact != nv && (contact == nextIndex(j, nv) || j == nextIndex(contact, nv)))
    return;
  const double keep = keepVertsSide ? -sigma : sigma;
  const Vec3 u = plane.n * (keep / std::sqrt(plane.nn));
  out.push_back({u, dot(u, a)});
}

// For edge i of `edges`: the planes through it touching `verts` from either rotation side (the
// vertex polygon entirely on the negative, resp. positive, side of the plane through the edge and
// the chosen vertex). Rotating about the edge's line, "w is beyond v" is transitive while the
// polygon spans less than a half-turn about it; when it does not, no plane through the edge has
// the polygon on one side and the exact test rejects the candidate.
void appendSeparatorsOfEdge(std::span<const Vec3> edges, size_t i, std::span<const Vec3> verts,
                            bool keepVertsSide, std::vector<ClipPlane>& out) {
  const size_t ne = edges.size(), nv = verts.size();
  const Vec3& a = edges[i];
  const Vec3 e = edges[nextIndex(i, ne)] - a;
  // A vertex on the edge's line lies on every plane through the edge and has no place in the
  // rotation order: it is never chosen (the exact test still sees it). The plane normal of a
  // vertex is only formed when it would be chosen.
  const double ee = lengthSquared(e);
  auto offAxis = [&](const Vec3& w, Vec3& n) {
    n = cross(e, w);
    return lengthSquared(n) > kAxisVertex * ee * lengthSquared(w);
  };
  size_t lo = nv, hi = nv;
  Vec3 nLo{}, nHi{}, n;
  for (size_t k = 0; k < nv; ++k) {
    const Vec3 w = verts[k] - a;
    if (lo == nv) {
      if (offAxis(w, n)) lo = hi = k, nLo = nHi = n;
      continue;
    }
    if (dot(nLo, w) > 0 && offAxis(w, n)) lo = k, nLo = n;
    if (dot(nHi, w) < 0 && offAxis(w, n)) hi = k, nHi = n;
  }
  if (lo == nv) return;
  // `verts` is on the negative side of lo's plane and the positive side of hi's: a separator has
  // the edge polygon on the other side, so a candidate whose next vertex of that polygon is
  // clearly on the same side is skipped without the exact test (skipping can only lose a plane).
  const Vec3 next = edges[nextIndex(nextIndex(i, ne), ne)] - a;
  const double nextLength2 = lengthSquared(next);
  auto clearly = [&](const Vec3& normal, double side) {
    const double s = side * dot(normal, next);
    return s > 0 && s * s > kClearSide * lengthSquared(normal) * nextLength2;
  };
  if (!clearly(nLo, -1)) acceptIfSeparator(edges, i, verts, lo, keepVertsSide, !keepVertsSide, out);
  if (hi != lo && !clearly(nHi, 1))
    acceptIfSeparator(edges, i, verts, hi, keepVertsSide, !keepVertsSide, out);
}

}  // namespace

void findSeparatingPlanes(std::span<const Vec3> source, std::span<const Vec3> pass,
                          std::vector<ClipPlane>& out) {
  out.clear();
  SeparatorCursor cursor;
  while (!cursor.done()) appendNextSeparators(source, pass, cursor, out);
}

void appendNextSeparators(std::span<const Vec3> source, std::span<const Vec3> pass,
                          SeparatorCursor& cursor, std::vector<ClipPlane>& out) {
  if (source.size() < 3 || pass.size() < 3) {
    cursor.family = 2;
    return;
  }
  // Family 0: edges of the source, vertices of the pass; family 1: the reverse.
  const bool first = cursor.family == 0;
  const std::span<const Vec3> edges = first ? source : pass, verts = first ? pass : source;
  appendSeparatorsOfEdge(edges, cursor.edge, verts, first, out);
  if (++cursor.edge == edges.size()) ++cursor.family, cursor.edge = 0;
}

}  // namespace gv
