// The spatial subdivision: convex cells, the portals between them and the adjacency graph they
// form — the output of paper §3 that visibility propagation (§4) walks.
#pragma once

#include <cstdint>
#include <vector>

#include "bsp/bsp_tree.h"
#include "geometry/convex_polygon.h"
#include "geometry/convex_polyhedron.h"
#include "scene/scene.h"

namespace gv {

/// What one boundary face of a cell touches. Face i of a cell is `Cell::shape.faces[i]`
/// (its polygon faces out of the cell); `Cell::faces[i]` describes it.
struct BoundaryFace {
  /// The BSP node whose plane holds the face, or -1 for a face of the root box (the world's
  /// boundary: nothing lies beyond it, no patch touches it, it has no portal).
  int32_t node = -1;
  /// Patches coaffine with the face that overlap it (in more than a sliver), either facing,
  /// sorted. Their union is the opaque part of the face.
  std::vector<uint32_t> coaffinePatches;
  /// Portals lying on this face (indices into Subdivision::portals), sorted.
  std::vector<uint32_t> portals;
};

/// One convex piece of a cell merged from several (visibility/convex_merge.h).
struct CellPart {
  ConvexPolyhedron shape;
  std::vector<uint32_t> patches;  ///< as Cell::patches, for this piece
  /// The cell's portals on this piece's boundary (indices into Subdivision::portals), sorted.
  std::vector<uint32_t> portals;
  /// The openings between this piece and the cell's other pieces (indices into
  /// Cell::innerPortals), sorted.
  std::vector<uint32_t> innerPortals;
};

/// An opening between two pieces of a merged cell: the BSP portal the merge dropped from the
/// cell graph, kept so that a search may walk the pieces one by one (patch_search.cpp). Its
/// polygon is counter-clockwise seen from piece `front` (as Portal's).
struct InnerPortal {
  ConvexPolygon polygon;
  uint32_t back = 0, front = 0;  ///< indices into Cell::parts
  uint32_t other(uint32_t part) const { return part == back ? front : back; }
};

/// A leaf cell of the BSP: a convex polyhedron of air (or of a solid's inside). After
/// mergeConvexCells a cell may also be a union of leaves: then `parts` lists them.
struct Cell {
  /// The cell (after mergeConvexCells possibly the convex union of several leaves); unset (no
  /// faces) when `parts` is not empty.
  ConvexPolyhedron shape;
  /// Empty, or the convex leaves of a cell that is not convex (no patch faces into any of them:
  /// visibility/convex_merge.h), each with its patches.
  std::vector<CellPart> parts;
  std::vector<InnerPortal> innerPortals;  ///< between the parts (empty when `parts` is)
  std::vector<BoundaryFace> faces;  ///< parallel to shape.faces (empty after mergeConvexCells)
  /// Patches inside the cell or on its boundary (coaffine with a face), sorted, no repeats.
  std::vector<uint32_t> patches;
  /// Patches on the boundary whose front looks into the cell as the BSP placed them (coaffine
  /// with a face whose outward normal opposes theirs), sorted. The BSP may put a patch on a plane
  /// tilted from its own within the model tolerance, so the cell's centroid can lie a hair
  /// behind the patch's own plane while the cell is the air in front of it (e3m4.map: a wedge
  /// 0.23 thick along a 288-unit wall); this list, not the centroid, says which way it looks.
  std::vector<uint32_t> facingPatches;
  /// Patches lying inside the cell rather than on its boundary (left by the stop rule), sorted.
  std::vector<uint32_t> interiorPatches;
  std::vector<uint32_t> portals;  ///< portals on the cell's boundary, sorted
};

/// A portal: a convex transparent part of the boundary between two cells. Its polygon is
/// counter-clockwise seen from `front`, i.e. its normal points from cell `back` into cell `front`;
/// it lies in the plane of BSP node `node`, inside a face of each of the two cells, and overlaps
/// no patch coaffine with those faces (beyond the length tolerance).
struct Portal {
  ConvexPolygon polygon;
  uint32_t back = 0, front = 0;  ///< the two cells it links (back ≠ front)
  int32_t node = 0;
  /// The cell on the other side from `cell` (which must be one of the two).
  uint32_t other(uint32_t cell) const { return cell == back ? front : back; }
};

/// The paper's §7.1 figures for one subdivision.
struct SubdivisionStats {
  size_t patches = 0, planes = 0, nodes = 0, cells = 0, portals = 0;
  int depth = 0;
  double meanFacesPerCell = 0;            ///< boundary faces per cell
  double meanCoaffinePatchesPerCell = 0;  ///< distinct patches coaffine with some face, per cell
  double meanPortalsPerCell = 0;          ///< portals on a cell's boundary, per cell
  double bspSeconds = 0, portalSeconds = 0;
  /// The stop rule the cells were built with (BspOptions::minCoverage).
  double minCoverage = 0;
  /// Of the patches' area, the part inside cells rather than on their boundaries: the surface
  /// the cells do not follow (the searches see it from every side of its cell).
  double interiorAreaFraction = 0;
  /// Of the cells, those with no portal: the sealed insides of closed solids (brushes), and
  /// cells cut off whole. Near 0 where walls are one-sided faces with the level's void behind.
  double sealedCellFraction = 0;
  /// Of the portals, those opening into a blind cell (no patch faces into it:
  /// somePatchFacesInto): the void behind one-sided walls, and the level's outside.
  double blindPortalFraction = 0;
};

/// Cells + portals = the adjacency graph over cells: two cells are adjacent iff a portal links
/// them. Built by `buildSubdivision`.
struct Subdivision {
  BspTree tree;
  std::vector<Cell> cells;  ///< cell i is tree.leaves[i], unless leafCell says otherwise
  std::vector<Portal> portals;
  SubdivisionStats stats;
  /// The cell holding each BSP leaf when cells were merged (visibility/convex_merge.h); empty when
  /// cell i is leaf i.
  std::vector<uint32_t> leafCell;

  /// The cell holding point p (by walking the BSP; a point on a boundary goes to one of its
  /// cells). p must be inside the root box.
  uint32_t cellAt(const Vec3& p) const {
    const uint32_t leaf = tree.leafAt(p);
    return leafCell.empty() ? leaf : leafCell[leaf];
  }
  /// The distinct cells linked to `cell` by a portal, sorted.
  std::vector<uint32_t> neighbours(uint32_t cell) const;
};

/// Builds the BSP (buildBspTree) and then the portals: for every node, the faces of the leaves
/// on its front side are intersected with those on its back side within the node's plane, and the
/// node's coplanar patch fragments are subtracted from each overlap; the convex pieces left (wider
/// than the length tolerance) are the portals. Any patch coaffine with a face is opaque there,
/// whichever way it faces, so a closed solid's inside is never linked to the air around it.
/// Throws std::invalid_argument for a scene without patches.
Subdivision buildSubdivision(const Scene& scene, const BspOptions& options = {});

/// Whether some patch faces into a convex cell of buildSubdivision: one lies inside it, the BSP
/// placed one facing in (Cell::facingPatches), or the cell's centroid is in front of one on its
/// boundary. The one facing rule of the searches, the live regions and the blind-cell merge.
bool somePatchFacesInto(const Scene& scene, const Cell& cell);

/// Cells that leave more of the surface than this inside them do not follow the scene. A patch
/// inside a cell is invisible to the searches (they see through the cell), and on real levels
/// the few such walls are the ones with the level's outside behind them, through which the
/// searches then reach the whole void: measured 2026-12-03 (docs/BENCHMARKS.md), the sector
/// levels at 14.5 % and 26 % inside listed 2-4x the pairs of the next finer rule (1-6 % inside)
/// and took longer; E1M1.map at 27.7 % 50.5 s and 12.6 % of pairs, at 4.5 % 25.3 s and 4.7 %.
/// The offices (3.9-5.7 % at the coarse rule) keep it.
inline constexpr double kMaxInteriorAreaFraction = 0.0625;

/// A finer rule that gives more portals than this per patch is not taken when the coarser one
/// already leaves at most kShatterInteriorAreaFraction of the surface inside its cells (it is
/// kept): splitting on every plane of an arena level fills its open space with slivers (measured:
/// q3-oa_ctf2 at rule 0 made 13,938 portals for 1,313 patches and took 10 s against 0.9 s at
/// 0.1; the sector levels and E1M1.map stay near 2-2.5 at every rule). A coarser rule that
/// leaves more inside (one cell holding everything, say) is never kept for this reason. 6, not
/// 4: Freedoom's MAP10 makes 4.14 portals per patch at rule 0.01, and keeping 0.03 instead left
/// 34 % of its surface inside cells and 1.7 times the pairs (3.83 M against 2.22 M); of 42
/// levels measured (session 32), no other one has a next rule between 4 and 10 per patch.
inline constexpr double kMaxPortalsPerPatch = 6.0;
inline constexpr double kShatterInteriorAreaFraction = 0.5;

/// A level built of closed solids (brush soups: Quake 3 arena levels as OBJ) rather than of
/// one-sided walls with the void behind them (sector levels, and Quake maps as the .map importer
/// gives them), as its subdivision shows: at least kClosedSolidsMinSealedCells of the cells
/// sealed (the solids' insides) and at most kClosedSolidsMaxBlindPortals of the portals opening
/// into blind cells (the void). There a face the stop rule leaves inside a cell mostly has the
/// other faces of its solid behind it, still on cell boundaries, so cells that follow fewer
/// faces cull nearly as much; behind a one-sided wall left inside a cell lies the void, through
/// which the searches reach everything. Measured on 54 levels at every rule they reach
/// (2026-12-07, docs/BENCHMARKS.md "Closed solids: coarser cells"), at rules 0.1-0.01: sealed
/// 0.067-0.29 of the cells on the 23 arena levels, at most 0.051 on the 31 sector levels and
/// Quake maps but for lqdm13.map at 0.1 (its few cells of the coarsest rule: 0.28, no blind
/// portal; the next rule's fall, 9.0 -> 2.0 % inside, keeps that finer rule); blind portals at
/// most 0.18 on the arena levels, at least 0.27 on the others.
inline constexpr double kClosedSolidsMinSealedCells = 0.06;
inline constexpr double kClosedSolidsMaxBlindPortals = 0.25;
bool builtOfClosedSolids(const SubdivisionStats& stats);

/// On a level built of closed solids, a rule finer than the coarsest that leaves at most
/// kClosedSolidsMaxInteriorAreaFraction of the area inside its cells is kept unless the next
/// rule leaves less than 1/kClosedSolidsMinInteriorReduction of that inside: what the next
/// rules would put on cell boundaries is then small detail, not walls, and their extra cells
/// mostly slice open space, where the cell searches fan out. Measured against the finer rules
/// the old choice took (one thread, 2026-12-07): q3-czest1dm at 0.1 (18.6 % inside, the next
/// rule 11.9 %) 959,981 pairs in 38.7 s against 961,764 in 145 s at rule 0; q3-oacmpdm4
/// (22.9 %, next 17.2 %) +4.4 % pairs in 11.8 s against 74 s; q3-oa_dm6 (20.7 %, 11.9 %) +2.5 %
/// in 13.5 s against 41.7 s; q3-oa_shouse (29.9 %, 14.2 %) +4.7 % in 37 s against 434 s. Not
/// kept: q3-oa_dm4 at 0.1 (15.3 %, next 0.9 %) listed 13 % more pairs, q3-oa_dm3 (35.4 %, next
/// 5.6 %) 38 % more. Both bounds sit between the levels measured (kept: the next rule leaves
/// 0.30-0.75 of the inside area on 11 levels; not kept: 0.06-0.16), not at a proven edge.
inline constexpr double kClosedSolidsMaxInteriorAreaFraction = 1.0 / 3.0;
inline constexpr double kClosedSolidsMinInteriorReduction = 4.0;

/// `vis`'s cells: buildSubdivision with each stop rule of kVisibilityCoverageSteps in turn
/// (`options.minCoverage` is not read), keeping the first whose cells hold at most
/// kMaxInteriorAreaFraction of the patches' area inside them, or on a level builtOfClosedSolids
/// the first finer than the coarsest that leaves at most kClosedSolidsMaxInteriorAreaFraction
/// inside and whose next rule would not divide that by kClosedSolidsMinInteriorReduction, or
/// the last before one with more than kMaxPortalsPerPatch portals per patch if that one leaves
/// at most kShatterInteriorAreaFraction inside. The coarse rule suits buildings (the default
/// office: 4 % inside, 0.04 s); real levels need the finer ones (a sector level is one cell at
/// 0.3 and 0.1; an arena level 84 % inside at 0.3, 5 % at 0.1). Every build is cheap next to the
/// searches; the progress callback sees each.
Subdivision buildVisibilitySubdivision(const Scene& scene, BspOptions options);

}  // namespace gv
