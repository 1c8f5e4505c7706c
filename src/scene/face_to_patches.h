// Turning one input face (any polygon) into convex planar patches: the import rules of issue #2.
#pragma once

#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"
#include "scene/scene.h"

namespace gv {

/// What happened to one face.
enum class FaceOutcome {
  Convex,        ///< planar and convex: one patch
  SplitConvex,   ///< planar, not convex: split into convex pieces along diagonals
  Triangulated,  ///< not planar within tolerance: triangulated
  Degenerate,    ///< fewer than 3 distinct vertices, zero area, or nothing usable left: dropped
};

struct FacePatches {
  FaceOutcome outcome = FaceOutcome::Degenerate;
  std::vector<ConvexPolygon> pieces;  ///< each with the face's orientation (front = CCW side)
};

/// Converts a face given counter-clockwise as seen from its front. A face is planar when every
/// vertex lies within kRelativeModelEpsilon × (face diameter) of its Newell plane. Planar
/// non-convex simple faces are partitioned into convex pieces (Hertel–Mehlhorn, via CGAL);
/// self-intersecting faces are fan-triangulated and the triangles that face backwards dropped.
/// Vertices of the output are input vertices: nothing is moved or re-projected.
/// `keepSlivers`: keep faces and pieces thinner than the model tolerance (isSliver), as a file
/// this tool wrote must read back face for face (scene/patches_obj.h); user input drops them.
FacePatches faceToPatches(const std::vector<Vec3>& face, const Tolerance& tol,
                          bool keepSlivers = false);

/// The largest distance between two of the vertices.
double diameterOf(const std::vector<Vec3>& vertices);

/// Zero width: twice the area over the diameter is a polygon's thickness scale. One narrower than
/// the model tolerance (a sliver left by a T-junction fix, 1e-4 of a short edge wide) is below the
/// scene's resolution: the BSP would merge the planes around it, and sightlines from it graze its
/// neighbours' planes at a depth the tolerance does not resolve. Import drops such faces and
/// pieces, and every later step that makes patches must too, so that patches.obj reads back as
/// the same patches.
bool isSliver(double twiceArea, double diameter, const Tolerance& tol);
inline bool isSliver(const ConvexPolygon& p, const Tolerance& tol) {
  return isSliver(2 * p.area(), diameterOf(p.vertices), tol);
}

/// Counts what happened to a face in the importer's report; false when the face was dropped.
bool countFaceOutcome(FaceOutcome outcome, ImportReport& report);

}  // namespace gv
