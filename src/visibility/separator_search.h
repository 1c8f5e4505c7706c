// Fast search for the separating planes of two convex portals (paper §4.1, Fig. 5): the planes
// `separatingPlanes` (portal_clipping.h) finds, found with O(edges x vertices) floating-point
// orientation tests instead of one candidate plane per (edge, vertex) pair, and each confirmed
// with the same exact test (separating_plane.h).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "geometry/vec3.h"
#include "visibility/portal_clipping.h"

namespace gv {

/// The separating planes of (source, pass), oriented to keep the pass's side, for clipping every
/// portal after `pass` (clipByPlanes). The same planes as `separatingPlanes(source, pass, out)`
/// (the same exact acceptance test, so each one is a valid separator and clipping by them never
/// removes a point of a stabbing line), found faster: through an edge of one polygon, the plane
/// rotating about the edge's line touches the other polygon last at one of two extreme vertices,
/// picked by one floating-point pass over its vertices; only those candidates run the exact test.
/// A plane touching the other polygon along an edge of it is listed once (not once per vertex).
/// A rounding misorder among nearly tied vertices can only lose a plane (a looser clip, still
/// conservative), never admit a wrong one.
void findSeparatingPlanes(std::span<const Vec3> source, std::span<const Vec3> pass,
                          std::vector<ClipPlane>& out);

/// Where a lazy run of findSeparatingPlanes stands: the planes through the edges of family 0
/// (edges of the source, vertices of the pass) and then family 1 (the reverse) before (family,
/// edge) have been appended.
struct SeparatorCursor {
  int family = 0;
  size_t edge = 0;
  bool done() const { return family >= 2; }
};

/// The lazy form of findSeparatingPlanes, one edge at a time: appends the planes through the
/// cursor's edge and advances it. Run from a fresh cursor until done(), it appends exactly the
/// planes of findSeparatingPlanes, in the same order; a caller clipping a portal can stop early
/// once the portal is clipped away.
void appendNextSeparators(std::span<const Vec3> source, std::span<const Vec3> pass,
                          SeparatorCursor& cursor, std::vector<ClipPlane>& out);

}  // namespace gv
