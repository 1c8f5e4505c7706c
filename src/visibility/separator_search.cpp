// Fast separating-plane search for two convex portals (paper §4.1). See separator_search.h; the
// exact acceptance test is separating_plane.h's, the one portal_clipping.cpp uses (whose proof in
// portal_clipping.h covers these planes).
#include "visibility/separator_search.h"

#include <cmath>

#include "visibility/separating_plane.h"

namespace gv {
namespace {

// A vertex whose sine of angle to the edge's line (squared) is below this is taken as on it.
constexpr double kAxisVertex = 1e-20;
// A point whose sine of angle to a candidate plane (squared) exceeds this is clearly on its side
// (far beyond rounding): the candidate is decided without the exact test.
constexpr double kClearSide = 1e-12;

// `secondFamily`: edges of the pass, vertices of the source. A plane touching the source along
// an edge of it holds an edge of each polygon, and the first family (edges of the source) has
// listed it already under the same conditions: it is not listed twice.
void acceptIfSeparator(std::span<const Vec3> edges, size_t i, std::span<const Vec3> verts, size_t j,
                       bool keepVertsSide, bool secondFamily, std::vector<ClipPlane>& out) {
  ClipPlane plane;
  const size_t nv = verts.size();
  size_t contact = nv;
  if (!exactSeparator(edges, i, verts, j, keepVertsSide, plane, contact)) return;
  if (secondFamily && contact != nv && (contact == nextIndex(j, nv) || j == nextIndex(contact, nv)))
    return;
  out.push_back(plane);
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
