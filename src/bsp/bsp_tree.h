// The BSP tree over a scene's patches, split by patch support planes with the paper's heuristic:
// its leaves are the convex cells of the spatial subdivision. Paper §3.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "bsp/plane_set.h"
#include "geometry/convex_polygon.h"
#include "geometry/convex_polyhedron.h"
#include "geometry/tolerance.h"
#include "scene/scene.h"

namespace gv {

/// The root volume is the scene's bounding box enlarged by this fraction of its diagonal on every
/// side (not the convex hull): every patch then lies strictly inside it, so the air around an
/// open or one-sided model forms cells too (a patch on the root's boundary would have no cell on
/// its outer side), and a flat scene (a single patch) still gets a solid root.
inline constexpr double kRootMarginFraction = 0.05;

/// The stop rule `vis` uses unless told otherwise. Splitting on every furniture plane fills free
/// space with thin cells that light crosses in many ways: on the default office the portal
/// searches ran 40x more stabbing tests (1.5 M vs 50 k) for 0.8 % fewer listed pairs (3,853 vs
/// 3,884; measured 2026-12-01, docs/BENCHMARKS.md). The paper's heuristic aims at the same:
/// no "free-space splitting" (§7.3).
inline constexpr double kVisibilityMinCoverage = 0.3;
/// The stop rules `vis` tries in turn, coarsest first (buildVisibilitySubdivision in
/// bsp/subdivision.h): on real levels no wall covers 0.3 of a section through many rooms, and the
/// coarse rule leaves the level one cell (sector levels) or a few cells holding most of the
/// surface (arena levels), where the searches then cull nothing.
inline constexpr double kVisibilityCoverageSteps[] = {kVisibilityMinCoverage, 0.1, 0.03, 0.01, 0.0};

/// Tuning of the BSP construction.
struct BspOptions {
  /// The stop rule ("while polygons of sufficient size are present"). A plane may split a cell
  /// only when the patch fragments on it inside the cell cover at least this fraction of the
  /// cell's section by that plane. 0 (the default) splits on every plane that still has a
  /// fragment inside the cell, so every patch ends on cell boundaries and no cell holds a patch
  /// in its interior; raising it (say 0.1) gives fewer, larger cells whose small patches
  /// (furniture, lights) stay inside them and are recorded as the cell's interior patches.
  double minCoverage = 0.0;
  /// A plane whose fragments in a cell total less than this fraction of the scene's diagonal
  /// squared never splits that cell (0: none is too small).
  double minRelativeArea = 0.0;
  /// At most this many planes (those with the largest fragment area in the cell) are scored per
  /// cell; the others wait for a smaller cell. Bounds the cost per node on large scenes.
  int maxCandidates = 48;
  /// Called after each leaf with the fraction of the root's volume in finished leaves (0..1];
  /// may be empty (then no volumes are computed).
  std::function<void(double)> progress;
};

/// A piece of a patch clipped to a BSP cell, on plane `plane` of the PlaneSet.
struct PatchFragment {
  uint32_t patch = 0;
  uint32_t plane = 0;
  /// The piece projected onto the merged plane (moved by at most Tolerance::planeOffset()),
  /// facing as the patch does.
  ConvexPolygon polygon;
};

/// A child reference: >= 0 is a node index, < 0 encodes leaf cell `leafOf(child)`.
inline constexpr int32_t leafChild(uint32_t leaf) {
  return -1 - static_cast<int32_t>(leaf);
}
inline constexpr uint32_t leafOf(int32_t child) {
  return static_cast<uint32_t>(-1 - child);
}

/// An internal node. Its splitting plane's front child holds the points with distance > 0.
struct BspNode {
  uint32_t plane = 0;  ///< index into BspTree::planes.planes()
  Plane splitter;      ///< that plane, as split on (normal points into `front`)
  int32_t front = 0, back = 0;
  /// The fragments of patches lying in this node's plane inside the node's cell (on the boundary
  /// between its two subtrees): the opaque parts of the node's section, used to cut portals.
  std::vector<PatchFragment> coplanar;
};

/// A leaf of the BSP: a convex cell.
struct BspLeaf {
  /// The cell. Each face's planeId is the BspNode whose plane it lies on, or -1 for a face of
  /// the root box (the world's boundary).
  ConvexPolyhedron shape;
  /// Fragments left inside the cell when it stopped splitting (empty with the default stop rule
  /// unless a plane only grazed the cell), and fragments lying on a plane that merely touches it.
  std::vector<PatchFragment> interior;
};

/// The tree. Node 0 is the root when `nodes` is non-empty; otherwise the root is leaf 0.
struct BspTree {
  Tolerance tol;
  PlaneSet planes;
  ConvexPolyhedron root;
  std::vector<BspNode> nodes;
  std::vector<BspLeaf> leaves;
  int depth = 0;  ///< the longest root-to-leaf path, in nodes

  /// The leaf whose cell holds p (points on a splitting plane go to the back).
  uint32_t leafAt(const Vec3& p) const;
};

/// Builds the BSP of the scene's patches (which must not be empty) by the paper's heuristic:
/// in each cell, a plane whose coplanar fragments cover the cell's whole section (the cut then
/// separates mutually invisible parts) is preferred; otherwise the plane whose fragments cover the
/// largest fraction of the section. Ties go to the plane nearest the cell's centre (a more
/// balanced tree). Every node's plane removes its fragments from both subtrees, so the depth is
/// at most the number of distinct planes. Throws std::invalid_argument for an empty scene.
BspTree buildBspTree(const Scene& scene, const BspOptions& options = {});

}  // namespace gv
