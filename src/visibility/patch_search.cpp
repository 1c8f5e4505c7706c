// Patch-to-patch searches (paper §4.2): pieces of patches placed in the cells, and the search
// from each patch, pruned by the stabbing test and by what is already seen (see patch_search.h).
#include "visibility/patch_search.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <mutex>
#include <optional>
#include <span>

#include "geometry/ball.h"
#include "geometry/ball_tree.h"
#include "util/parallel_for.h"
#include "visibility/facing_lines.h"
#include "visibility/patch_grid.h"
#include "visibility/search_deadline.h"

namespace gv {
namespace {

/// A patch's piece inside (or on the boundary of) one cell, and which way its front looks.
struct CellPatch {
  uint32_t patch = 0;
  ConvexPolygon piece;
  bool facesIn = false;   ///< the front looks into the cell
  bool interior = false;  ///< lies inside the cell: sightlines may meet either side
  bool whole = false;     ///< the piece is the whole patch
  /// The BSP placed the patch facing one way and the cell's centroid says the other: a patch
  /// moved onto a plane tilted from its own (see placePatches).
  bool tilted = false;
  /// The cell's boundary plane the piece lies on (every vertex within the BSP's plane-merging
  /// slack of it), or -1. Two pieces on one boundary plane see each other only along lines
  /// within that slack of the plane, where a third piece merged onto it may stand.
  int32_t boundaryPlane = -1;
  /// In a cell merged from several leaves, the leaf (index into Cell::parts) the piece was
  /// placed in; -1 in a convex cell.
  int32_t part = -1;
  /// Placed by placeThinWallSlivers: in a merged cell, searched leaf by leaf (visitPart).
  bool sliver = false;
  /// A ball holding the piece (placePatches sets it last): the over-budget answer's first test.
  Ball ball;
};

/// The part of p within the cell, grown by the BSP's plane-merging tolerance so that pieces moved
/// onto merged planes are never lost (a larger piece only makes the search see more).
std::optional<ConvexPolygon> clipToCell(const ConvexPolygon& p, const ConvexPolyhedron& cell,
                                        const Tolerance& tol) {
  std::optional<ConvexPolygon> cur = p;
  const double slack = tol.planeOffset();
  for (const Plane& h : cell.halfspaces) {
    cur = clipToFront(*cur, Plane{-h.normal, -h.offset - slack}, tol);  // keep h.distance <= slack
    if (!cur) return std::nullopt;
  }
  return cur;
}

/// The index of the halfspace of `cell` whose plane every vertex of `piece` lies within the
/// BSP's plane-merging slack of (from either side, as the pieces merged onto it do), or -1.
int32_t boundaryPlaneOf(const ConvexPolygon& piece, const ConvexPolyhedron& cell,
                        const Tolerance& tol) {
  const double slack = 2 * tol.planeOffset();
  for (size_t h = 0; h < cell.halfspaces.size(); ++h) {
    const Plane& plane = cell.halfspaces[h];
    if (std::all_of(piece.vertices.begin(), piece.vertices.end(),
                    [&](const Vec3& v) { return std::abs(plane.distance(v)) <= slack; }))
      return static_cast<int32_t>(h);
  }
  return -1;
}

/// The flags a search can give a patch through this piece of it.
uint8_t attainable(const CellPatch& cp) {
  return (cp.facesIn || cp.interior) ? (kSeen | kSeenFront) : kSeen;
}

using Placements = std::vector<std::vector<std::pair<uint32_t, size_t>>>;

/// Pieces of patches per cell, and where each patch lies: placements[p] lists (cell, index in
/// cellPatches[cell]) of p's pieces.
struct PatchPlacement {
  std::vector<std::vector<CellPatch>> cellPatches;
  Placements placements;
  size_t thinWallSlivers = 0;  ///< pieces placed by placeThinWallSlivers
  size_t acrossPortals = 0;    ///< pieces placed by placeAcrossCoplanarPortals
  size_t acrossThinSlabs = 0;  ///< pieces placed by placeAcrossThinSlabs
  /// Per cell, a ball hierarchy over its pieces (items: indices into cellPatches[cell]); its
  /// root holds them all.
  std::vector<BallTree> cellTrees;
  /// The pieces that only rays slipping into the outside at a wall's end look for, kept apart
  /// from cellPatches (so every other search walks the cells and ball trees it walked without
  /// them): `slivers`, placed by placeThinWallSlivers in the leaves of merged cells, and
  /// `fragments`, the parts of the front pieces of patches whose front looks beyond the air
  /// within the box of those parts (Scene::beyondAirBounds). A search from a sliver looks only
  /// for fragments, from a fragment only for slivers (PatchSearch::run).
  struct CellPiece {
    uint32_t cell = 0;
    CellPatch piece;
    /// For a sliver, the planes of the walls a ray leaving it crosses within the slack of its
    /// start, each facing the cell: such a ray goes on in front of the wall it crossed, so only
    /// pieces with a part there can be its next hit (mayMeetAcross).
    std::vector<Plane> crossed;
  };
  std::vector<CellPiece> slivers, fragments;
};

/// The part of `a` within `slab` of the plane of `w` and on the inner side of each of w's edges
/// moved out by `edge` (inwards when negative): the prism over w, widened or narrowed.
std::optional<ConvexPolygon> clipToPrism(const ConvexPolygon& a, const ConvexPolygon& w,
                                         double slab, double edge, const Tolerance& tol) {
  std::optional<ConvexPolygon> cur = a;
  const Plane& wp = w.plane;
  cur = clipToFront(*cur, Plane{-wp.normal, -wp.offset - slab}, tol);
  if (cur) cur = clipToFront(*cur, Plane{wp.normal, wp.offset - slab}, tol);
  const size_t n = w.vertices.size();
  for (size_t i = 0; cur && i < n; ++i) {
    const Vec3& a0 = w.vertices[i];
    const Vec3 out = normalize(cross(w.vertices[(i + 1) % n] - a0, wp.normal));
    cur = clipToFront(*cur, Plane{-out, -dot(out, a0) - edge}, tol);  // out·x <= out·a0 + edge
  }
  return cur;
}

/// The part of `a` within `slack` of `w` (clipped to the slab of w's plane and the prism over w's
/// edges, each widened by slack: a little more than the true distance near w's corners, which
/// only keeps more), or nullopt when no point of `a` is that close.
std::optional<ConvexPolygon> nearPart(const ConvexPolygon& a, const ConvexPolygon& w, double slack,
                                      const Tolerance& tol) {
  const Aabb ab = a.bounds(), wb = w.bounds();
  if (ab.lo.x > wb.hi.x + slack || wb.lo.x > ab.hi.x + slack || ab.lo.y > wb.hi.y + slack ||
      wb.lo.y > ab.hi.y + slack || ab.lo.z > wb.hi.z + slack || wb.lo.z > ab.hi.z + slack)
    return std::nullopt;
  return clipToPrism(a, w, slack, slack, tol);
}

/// The part of `a` inside the box `b` (a convex polygon: `a` clipped by six planes), or nullopt.
std::optional<ConvexPolygon> clipToBox(const ConvexPolygon& a, const Aabb& b,
                                       const Tolerance& tol) {
  std::optional<ConvexPolygon> cur = a;
  for (int axis = 0; axis < 3 && cur; ++axis) {
    Vec3 n{0, 0, 0};
    n[axis] = 1;
    cur = clipToFront(*cur, Plane{n, b.lo[axis]}, tol);
    if (cur) cur = clipToFront(*cur, Plane{-n, -b.hi[axis]}, tol);
  }
  return cur;
}

/// Slivers across thin walls. A patch S ending against a one-sided wall W (a face with air
/// behind it: a cell B whose boundary W lies on sees W's back) is not listed in B, yet a ray may
/// leave S within the model tolerance of W, cross W within that distance of its start (the
/// contact rule of `verify` and of the outside checks does not count such a hit) and go on
/// through B: on q3-oa_dm2, 2 rays in 10^6 did. So the part of S within the BSP's slack of B
/// becomes a piece of S in B too, searched from and searched for, when
/// - B is a convex cell with no patch inside it (its air is all behind W) and a patch faces into
///   it from a boundary plane that no patch facing away shares (it is air, not a solid's inside
///   seen by hidden faces), or, with `outside` (PropagationOptions::outsideSlivers), B is any
///   leaf of a merged cell (the level's outside; the piece is then searched leaf by leaf,
///   PatchSearch::visitPart, which finds only backs where the leaf is a solid's inside),
/// - either W faces away from B, S reaches W's front side, and the part of W strictly in front of
///   S comes within the slack of that piece (a ray leaving S's front can cross it),
/// - or W faces into B with S behind it (a solid's far side, or the back of a one-sided wall),
///   the part of W strictly in front of S comes within the slack of the piece (a ray leaving S
///   crosses W from behind: on e3m4 a wedge of air between S and a brush's corner, the ray
///   cutting the corner, 1 ray in 10^6), and no portal of B into a cell S is placed in passes
///   within the slack of those parts (there rays a slack beside it reach B through the opening
///   and are searched from S's own piece: a ledge, a step; only a pocket of air shut by the
///   solid's corner needs the sliver). Only those parts (their box) become the piece, and
/// - part of B lies in front of S.
/// A convex cell with patches inside it (left by the stop rule) gets the slivers across walls
/// facing into it only (q3-oacmpdm1: a wall under the edge of a floor, facing into the solid
/// under it, and above the floor a slot of air holding an arch's corner, so a patch inside; 1 of
/// 10^6 `verify` rays crossed the floor from behind at 1e-6; +1.3 % pairs there).
/// By default a leaf of a merged cell gets its slivers apart (PatchPlacement::slivers). On the
/// sector levels
/// every room ends at one-sided walls with the outside behind them, and a search from such a
/// sliver for everything lists 2.4-4.5 times the pairs (`outside`, docs/BENCHMARKS.md): from
/// the outside the search enters every room through cells that the stop rule left holding both
/// air and outside. But a ray that slipped through W into the void or a solid's inside first
/// meets either a back (blocked) or a front that looks out of the air there (doom-fd2-map19:
/// the part of a wall 2008 below the floor of the room it faces, a lower wall taller than that
/// room; the ray left a pillar's wall 1e-4 from its corner and crossed the next wall 1.66e-4
/// along), so only the parts of fronts the hidden-face pass found so (Scene::beyondAirBounds;
/// none known: no such sliver) are looked for from it, and only they look for it.
/// Behind a wall facing away from a convex cell with patches inside it, or from a convex cell
/// that is not air by the test below, the air is not known without a finer test; a ray that
/// crosses such a wall into a solid meets backs or fronts looking beyond the air first, so there
/// the sliver goes to PatchPlacement::slivers too and looks for those fronts only.
/// Returns the number of pieces placed (PatchPlacement::slivers among them).
size_t placeThinWallSlivers(const Scene& scene, const Subdivision& sub, const Tolerance& tol,
                            bool outside, PatchPlacement& out) {
  const bool beyondAirTargets =
      std::any_of(scene.beyondAirBounds.begin(), scene.beyondAirBounds.end(),
                  [](const Aabb& b) { return !b.empty(); });
  std::vector<Aabb> boxes;
  boxes.reserve(scene.patches.size());
  for (const Patch& p : scene.patches) boxes.push_back(p.polygon.bounds());
  const PatchGrid grid(boxes);
  const double slack = tol.planeOffset();
  // The part of `piece` from which a ray leaving S's front can cross the wall `w` of the cell
  // within the slack of its start, or nullopt: S must reach the side of W's plane away from the
  // cell (in front of W when W faces away from the cell, behind it when W faces into it), and the
  // part of W strictly in front of S must come within the slack of the piece.
  auto nearWallPart = [&](const ConvexPolygon& s, const ConvexPolygon& piece,
                          const CellPatch& w) -> std::optional<ConvexPolygon> {
    const Plane& wp = scene.patches[w.patch].polygon.plane;
    const double away = w.facesIn ? -1 : 1;  // the sign of W's side away from the cell
    if (std::none_of(s.vertices.begin(), s.vertices.end(),
                     [&](const Vec3& v) { return away * wp.distance(v) > tol.length(); }))
      return std::nullopt;  // S stays on the cell's side of W or on its plane: it cannot cross W
    const auto ahead =
        clipToFront(w.piece, Plane{s.plane.normal, s.plane.offset + tol.length()}, tol);
    if (!ahead) return std::nullopt;
    return nearPart(piece, *ahead, slack, tol);
  };
  std::vector<uint32_t> near;
  size_t placed = 0;
  // One convex region B of cell c: the cell itself, or one leaf (part) of a merged cell, with the
  // patches the BSP placed on it and the indices of their pieces in cellPatches[c].
  auto slivers = [&](uint32_t c, const ConvexPolyhedron& shape,
                     const std::vector<uint32_t>& patches, const std::vector<uint32_t>& portals,
                     int32_t part, bool facingInOnly) {
    // facingInOnly: only walls facing into B (B has patches inside it).
    std::vector<size_t> mine;  // B's own pieces (slivers placed below are not among them)
    for (size_t k = 0; k < out.cellPatches[c].size(); ++k)
      if (out.cellPatches[c][k].part == part) mine.push_back(k);
    const std::vector<CellPatch>& listed = out.cellPatches[c];
    std::vector<size_t> walls;  // the BSP-listed pieces of B that face away from it
    for (size_t k : mine)
      if (!listed[k].facesIn) walls.push_back(k);
    // B is air when a patch faces into it from a boundary plane that no patch facing away shares
    // (a face covered by a coincident one facing away is a solid's hidden face: a floor under a
    // wall box). In a solid's inside a ray that crossed W would see only backs of faces.
    const bool air = std::any_of(mine.begin(), mine.end(), [&](size_t i) {
      const CellPatch& in = listed[i];
      return in.facesIn &&
             (in.boundaryPlane < 0 || std::none_of(walls.begin(), walls.end(), [&](size_t k) {
                return listed[k].boundaryPlane == in.boundaryPlane;
              }));
    });
    // A leaf of a merged cell has no patch facing into it as the BSP placed it (a piece may face
    // in by the leaf's centroid), and whether air lies behind W is not known there: with
    // `outside` every leaf is taken for air, and the leaf walk finds what a ray crossing W could
    // reach (in a solid's inside, only backs); without it the slivers look only for fronts
    // facing beyond the air (the air test above, applied to leaves, added 2.2 % pairs on e3m4
    // and fixed no miss).
    // A convex cell with patches inside it, or one that is not air by the test above: what lies
    // behind a wall facing away from it is not known (the stop rule left air and solid in one
    // cell), so a piece of S across such a wall looks only for fronts facing beyond the air, as
    // in a leaf (q3-ctf_gate1: a ledge's underside ending on a wall whose brush stands on a beam
    // over a block that a floor runs through; a ray leaving the ledge crossed the wall 2.1e-4
    // from its start, inside the model tolerance, and met the floor's buried part first).
    const bool awayForFragmentsOnly = part < 0 && (facingInOnly || !air);
    if (part >= 0 ? !(outside || beyondAirTargets) : !(air || beyondAirTargets)) return;
    near.clear();
    grid.gather(shape.bounds(), 2 * slack, near);
    std::sort(near.begin(), near.end());
    for (uint32_t p : near) {
      if (std::binary_search(patches.begin(), patches.end(), p)) continue;
      const ConvexPolygon& poly = scene.patches[p].polygon;
      const PlaneSide side = shape.classify(poly.plane, tol);
      if (side != PlaneSide::Front && side != PlaneSide::Spanning) continue;
      auto piece = clipToCell(poly, shape, tol);
      if (!piece) continue;
      auto sliver = [&](ConvexPolygon&& sp) {
        CellPatch cp;
        cp.patch = p;
        cp.facesIn = true;
        cp.interior = side == PlaneSide::Spanning;
        cp.part = part;
        cp.sliver = true;
        cp.boundaryPlane = boundaryPlaneOf(sp, shape, tol);
        cp.piece = std::move(sp);
        ++placed;
        return cp;
      };
      // The walls a ray from the piece crosses near its start, facing B (CellPiece::crossed).
      auto crossedWalls = [&] {
        std::vector<Plane> planes;
        for (size_t k : mine)
          if (nearWallPart(poly, *piece, listed[k])) {
            const Plane& w = scene.patches[listed[k].patch].polygon.plane;
            planes.push_back(listed[k].facesIn ? w : w.flipped());
          }
        return planes;
      };
      if (awayForFragmentsOnly) {
        // Only the box of the parts near such walls, as below: these searches are many.
        Aabb box;
        if (beyondAirTargets)
          for (size_t k : walls)
            if (const std::optional<ConvexPolygon> close = nearWallPart(poly, *piece, listed[k]))
              box.add(close->bounds());
        if (!box.empty())
          if (std::optional<ConvexPolygon> strip = clipToBox(*piece, box.grown(tol.length()), tol))
            out.slivers.push_back({c, sliver(std::move(*strip)), crossedWalls()});
        if (!air) continue;  // the slivers below are for air
      }
      const bool crosses = !facingInOnly && std::any_of(walls.begin(), walls.end(), [&](size_t k) {
        return nearWallPart(poly, *piece, listed[k]).has_value();  // p is not listed in B
      });
      if (!crosses) {
        // Only the box of the parts near such walls: a ray from elsewhere on the piece would
        // cross them further than the slack from its start. Where an opening of the cell into a
        // cell S is placed in passes within a few slacks of all of such a part, rays a slack beside
        // the ones cutting through the wall reach the cell through that opening and are searched
        // from S there (a wall S ends at from behind: a ledge, a step); only the parts no such
        // opening runs along, as in a wedge of air shut by a solid's corner, or a wall standing
        // on a ledge's edge beside an opening, need the sliver. (Without this test q3-oa_dm2
        // listed 11 % more pairs, q3-dm4ish 7 %. Tested on the boxes of the opening and of all
        // the parts together instead, it dropped the sliver where an opening passed by one end
        // of a long edge, and q3-aggressor missed a pair whose ray crossed a wall standing on
        // the edge's other end, 4 units from the opening.)
        // A part near a wall is itself up to about two slacks across (at a corner, both ways):
        // an opening within a few slacks of each of its corners runs along all of it.
        constexpr double kOpeningReach = 4;
        // The opening must be one S's front looks through from its piece in that cell: not one
        // lying in S's own plane, where no stabbing line from S goes (q3-oacmpdm1: a slab's top
        // ending under a one-sided wall, the floor of the cell beyond the wall an opening in the
        // slab top's plane; 1 of 10^6 `verify --contact 1e-5` rays).
        auto looksThrough = [&](const Portal& portal, uint32_t o) {
          const bool inPlane =
              std::all_of(portal.polygon.vertices.begin(), portal.polygon.vertices.end(),
                          [&](const Vec3& v) { return std::abs(poly.plane.distance(v)) <= slack; });
          return !inPlane && std::any_of(out.placements[p].begin(), out.placements[p].end(),
                                         [&](const auto& pl) {
                                           if (pl.first != o) return false;
                                           const CellPatch& there = out.cellPatches[o][pl.second];
                                           return there.facesIn || there.interior;
                                         });
        };
        auto openingAlong = [&](const ConvexPolygon& close) {
          return std::any_of(portals.begin(), portals.end(), [&](uint32_t q) {
            const Portal& portal = sub.portals[q];
            const uint32_t o = portal.other(c);
            return portal.polygon.bounds().meets(close.bounds(), slack) &&
                   looksThrough(portal, o) &&
                   std::all_of(close.vertices.begin(), close.vertices.end(), [&](const Vec3& v) {
                     return distance(v, portal.polygon.nearestPoint(v)) <= kOpeningReach * slack;
                   });
          });
        };
        Aabb box;
        for (size_t k : mine)
          if (listed[k].facesIn)
            if (const std::optional<ConvexPolygon> close = nearWallPart(poly, *piece, listed[k]))
              if (!openingAlong(*close)) box.add(close->bounds());
        if (box.empty()) continue;
        piece = clipToBox(*piece, box.grown(tol.length()), tol);
        if (!piece) continue;
      }
      if (part >= 0 && !outside) {
        std::vector<Plane> planes = crossedWalls();
        out.slivers.push_back({c, sliver(std::move(*piece)), std::move(planes)});
        continue;
      }
      out.placements[p].emplace_back(c, out.cellPatches[c].size());
      out.cellPatches[c].push_back(sliver(std::move(*piece)));
    }
  };
  for (uint32_t c = 0; c < sub.cells.size(); ++c) {
    const Cell& cell = sub.cells[c];
    if (cell.parts.empty()) {
      slivers(c, cell.shape, cell.patches, cell.portals, -1, !cell.interiorPatches.empty());
    } else if (cell.interiorPatches.empty()) {
      for (size_t k = 0; k < cell.parts.size(); ++k) {
        const CellPart& leaf = cell.parts[k];
        slivers(c, leaf.shape, leaf.patches, leaf.portals, static_cast<int32_t>(k), false);
      }
    }
  }
  return placed;
}

/// Whether `a` comes within `slack` of the plane of `w` somewhere more than `slack` inside w's
/// edges: an overlap, not a neighbour in the plane sharing an edge.
bool overlapsInside(const ConvexPolygon& a, const ConvexPolygon& w, double slack,
                    const Tolerance& tol) {
  const std::optional<ConvexPolygon> inside = clipToPrism(a, w, slack, -slack, tol);
  return inside && inside->area() > 0;
}

/// Pieces of patches across the openings that overlap them. The BSP may move a patch onto a
/// plane tilted from its own within the model tolerance and leave, between that plane and the
/// patch's own, a wedge of a cell a hair thick whose boundary on the patch's own plane is an
/// opening: the patch is placed in the wedge only, and its front looks out of the wedge through
/// that opening, which lies on the patch. A sightline leaving the front there crosses the opening
/// in its plane, where no stabbing line goes, so the search from the wedge never reaches the air
/// in front (lq_e4m4: a ramp face in a wedge 0.12 thick at its widest end, its two misses in
/// 10^6 `verify` rays). So a patch with a piece in a cell whose portal lies along the patch's
/// plane and overlaps it is also placed in the cell across that portal, facing as that cell's
/// centroid says, and never as a whole piece (the same-cell shortcut stays with exact pieces).
/// Extra pieces only let the searches see more: the test for "along the plane" may be generous.
/// Returns the number of pieces placed.
size_t placeAcrossCoplanarPortals(const Scene& scene, const Subdivision& sub, const Tolerance& tol,
                                  PatchPlacement& out) {
  // Normals within about 2.6 degrees: the BSP's merged planes differ by far less.
  constexpr double kCoplanarCos = 0.999;
  const double slack = tol.planeOffset();
  struct Extra {
    uint32_t cell;
    CellPatch piece;
  };
  std::vector<Extra> extras;
  for (uint32_t c = 0; c < sub.cells.size(); ++c) {
    const Cell& cell = sub.cells[c];
    for (const CellPatch& cp : out.cellPatches[c]) {
      const ConvexPolygon& poly = scene.patches[cp.patch].polygon;
      const Aabb box = cp.piece.bounds();
      for (uint32_t q : cell.portals) {
        const Portal& portal = sub.portals[q];
        const uint32_t o = portal.other(c);
        if (!portal.polygon.bounds().meets(box, slack)) continue;
        if (std::abs(dot(portal.polygon.plane.normal, poly.plane.normal)) < kCoplanarCos) continue;
        const auto& placed = out.placements[cp.patch];
        if (std::any_of(placed.begin(), placed.end(),
                        [&](const auto& pl) { return pl.first == o; }))
          continue;
        if (!overlapsInside(cp.piece, portal.polygon, slack, tol)) continue;
        const Cell& other = sub.cells[o];
        auto add = [&](const ConvexPolyhedron& shape, int32_t part) {
          std::optional<ConvexPolygon> piece = clipToCell(poly, shape, tol);
          if (!piece) return;
          CellPatch extra;
          extra.patch = cp.patch;
          extra.facesIn = poly.plane.distance(shape.centroid()) > 0;
          extra.boundaryPlane = boundaryPlaneOf(*piece, shape, tol);
          extra.part = part;
          extra.piece = std::move(*piece);
          extras.push_back({o, std::move(extra)});
        };
        if (other.parts.empty()) {
          add(other.shape, -1);
        } else {
          for (size_t k = 0; k < other.parts.size(); ++k)
            add(other.parts[k].shape, static_cast<int32_t>(k));
        }
      }
    }
  }
  // Placed after the scan, so that a piece placed here does not spread across further openings;
  // the same piece reached through two openings of one cell is placed once.
  size_t placed = 0;
  for (Extra& e : extras) {
    auto& where = out.placements[e.piece.patch];
    if (std::any_of(where.begin(), where.end(), [&](const auto& pl) {
          return pl.first == e.cell &&
                 out.cellPatches[e.cell][pl.second].piece.vertices == e.piece.piece.vertices;
        }))
      continue;
    where.emplace_back(e.cell, out.cellPatches[e.cell].size());
    out.cellPatches[e.cell].push_back(std::move(e.piece));
    ++placed;
  }
  return placed;
}

/// Pieces of patches across sealed slabs thinner than the tolerance. Planes that run, or meet, a
/// hair in front of a patch (closer than the model tolerance, yet not merged with its plane) cut
/// a slab or wedge of a cell there; every face of it is a sliver at that tolerance, so none is a
/// portal (bsp/portals.cpp), and the patch's front looks into a cell with no way out: its search
/// sees nothing and it is listed with nothing, though its sightlines leave the slab within the
/// tolerance (q3-oa_rpg3dm2: patch 3683, a bevel 5.6e-4 tall between a beam's two sloped faces,
/// whose planes meet 2.2e-4 in front of it; `verify --unlisted-pairs` found a free segment from
/// it). So a piece facing into a cell without portals whose depth along the piece's normal is
/// within the slack (2 planeOffset) is also placed, as clipToCell keeps it, in every convex
/// region (a cell, or a leaf of a merged cell) within the slack of it with part of that region in
/// front of the patch, facing into it: the search from there sees what the patch's front sees
/// beyond the slab. Extra pieces only let the searches see more. Returns the number placed.
size_t placeAcrossThinSlabs(const Scene& scene, const Subdivision& sub, const Tolerance& tol,
                            PatchPlacement& out) {
  const double slack = 2 * tol.planeOffset();
  struct Stranded {
    uint32_t patch, cell;
  };
  std::vector<Stranded> stranded;
  std::vector<Aabb> boxes;  // per stranded piece, its box
  for (uint32_t c = 0; c < sub.cells.size(); ++c) {
    const Cell& cell = sub.cells[c];
    if (!cell.portals.empty() || !cell.parts.empty()) continue;
    for (const CellPatch& cp : out.cellPatches[c]) {
      if (!cp.facesIn) continue;
      const Vec3& n = scene.patches[cp.patch].polygon.plane.normal;
      double lo = INFINITY, hi = -INFINITY;
      for (const PolyhedronFace& f : cell.shape.faces)
        for (const Vec3& v : f.polygon.vertices) {
          lo = std::min(lo, dot(n, v));
          hi = std::max(hi, dot(n, v));
        }
      if (!(hi - lo <= slack)) continue;
      stranded.push_back({cp.patch, c});
      boxes.push_back(cp.piece.bounds());
    }
  }
  if (stranded.empty()) return 0;
  const PatchGrid grid(boxes);
  std::vector<uint32_t> near;
  size_t placed = 0;
  // Each convex region once (its bounds are computed from its faces), with the stranded pieces
  // whose boxes come within the slack of it, in their order.
  auto region = [&](uint32_t c, const ConvexPolyhedron& shape, int32_t part) {
    near.clear();
    grid.gather(shape.bounds(), slack, near);
    std::sort(near.begin(), near.end());
    for (uint32_t i : near) {
      const Stranded& st = stranded[i];
      if (c == st.cell) continue;
      const ConvexPolygon& poly = scene.patches[st.patch].polygon;
      // Part of the region in front of the patch: a line leaving its front can go on there.
      const PlaneSide side = shape.classify(poly.plane, tol);
      if (side != PlaneSide::Front && side != PlaneSide::Spanning) continue;
      std::optional<ConvexPolygon> piece = clipToCell(poly, shape, tol);
      if (!piece) continue;
      const std::vector<std::pair<uint32_t, size_t>>& where = out.placements[st.patch];
      if (std::any_of(where.begin(), where.end(), [&](const auto& pl) {
            return pl.first == c && out.cellPatches[c][pl.second].part == part;
          }))
        continue;  // already there
      CellPatch cp;
      cp.patch = st.patch;
      cp.facesIn = true;
      cp.interior = side == PlaneSide::Spanning;
      cp.part = part;
      cp.sliver = part >= 0;
      cp.boundaryPlane = boundaryPlaneOf(*piece, shape, tol);
      cp.piece = std::move(*piece);
      out.placements[st.patch].emplace_back(c, out.cellPatches[c].size());
      out.cellPatches[c].push_back(std::move(cp));
      ++placed;
    }
  };
  for (uint32_t c = 0; c < sub.cells.size(); ++c) {
    const Cell& cell = sub.cells[c];
    if (cell.parts.empty()) {
      region(c, cell.shape, -1);
    } else {
      for (size_t k = 0; k < cell.parts.size(); ++k)
        region(c, cell.parts[k].shape, static_cast<int32_t>(k));
    }
  }
  return placed;
}

/// The fragments (PatchPlacement::fragments): each front piece of a patch whose front looks
/// beyond the air, cut to the box of those parts (grown by the BSP's slack).
void placeBeyondAirFragments(const Scene& scene, const Tolerance& tol, PatchPlacement& out) {
  const double slack = 2 * tol.planeOffset();
  for (uint32_t t = 0; t < scene.beyondAirBounds.size() && t < out.placements.size(); ++t) {
    const Aabb& box = scene.beyondAirBounds[t];
    if (box.empty()) continue;
    const Aabb grown = box.grown(slack);
    for (auto [cell, k] : out.placements[t]) {
      const CellPatch& cp = out.cellPatches[cell][k];
      if (!cp.facesIn && !cp.interior) continue;
      std::optional<ConvexPolygon> piece = clipToBox(cp.piece, grown, tol);
      if (!piece) continue;
      CellPatch f = cp;
      f.piece = std::move(*piece);
      f.whole = false;
      f.ball = ballAround(f.piece.vertices, tol);
      out.fragments.push_back({cell, std::move(f)});
    }
  }
}

PatchPlacement placePatches(const Scene& scene, const Subdivision& sub, const Tolerance& tol,
                            bool outsideSlivers) {
  PatchPlacement out;
  std::vector<std::vector<CellPatch>>& cellPatches = out.cellPatches;
  Placements& placements = out.placements;
  cellPatches.resize(sub.cells.size());
  placements.resize(scene.patches.size());
  for (uint32_t c = 0; c < sub.cells.size(); ++c) {
    const Cell& cell = sub.cells[c];
    // A cell merged from several convex leaves is placed leaf by leaf (each piece faces in or out
    // of its own leaf); a convex cell is its own single part.
    auto place = [&](const ConvexPolyhedron& shape, const std::vector<uint32_t>& patches,
                     const std::vector<uint32_t>& facing, int32_t part) {
      const Vec3 inside = shape.centroid();
      for (uint32_t p : patches) {
        const ConvexPolygon& poly = scene.patches[p].polygon;
        auto piece = clipToCell(poly, shape, tol);
        if (!piece) continue;
        CellPatch cp;
        cp.patch = p;
        cp.interior =
            std::binary_search(cell.interiorPatches.begin(), cell.interiorPatches.end(), p);
        // As the BSP placed it, or by the cell's centroid. When the two disagree (a patch the
        // BSP moved onto a plane tilted from its own), both sides are searched for, as for a
        // patch inside the cell: the front test finds what sees its front, the back test keeps
        // it a blocker for lines that meet its own plane's back.
        const bool placedFacing = std::binary_search(facing.begin(), facing.end(), p);
        const bool centroidFacing = poly.plane.distance(inside) > 0;
        cp.facesIn = placedFacing || centroidFacing;
        if (placedFacing != centroidFacing) cp.interior = cp.tilted = true;
        cp.whole = piece->area() >= poly.area() * (1 - 1e-9);
        cp.part = part;
        cp.boundaryPlane = boundaryPlaneOf(*piece, shape, tol);
        cp.piece = std::move(*piece);
        placements[p].emplace_back(c, cellPatches[c].size());
        cellPatches[c].push_back(std::move(cp));
      }
    };
    if (cell.parts.empty()) {
      place(cell.shape, cell.patches, cell.facingPatches, -1);
    } else {
      // Blind leaves: no patch faces into them as the BSP placed it.
      for (size_t k = 0; k < cell.parts.size(); ++k)
        place(cell.parts[k].shape, cell.parts[k].patches, {}, static_cast<int32_t>(k));
    }
  }
  out.acrossPortals = placeAcrossCoplanarPortals(scene, sub, tol, out);
  out.acrossThinSlabs = placeAcrossThinSlabs(scene, sub, tol, out);
  out.thinWallSlivers = placeThinWallSlivers(scene, sub, tol, outsideSlivers, out);
  out.cellTrees.resize(sub.cells.size());
  std::vector<Ball> balls;
  for (size_t c = 0; c < sub.cells.size(); ++c) {
    balls.clear();
    for (CellPatch& cp : cellPatches[c])
      balls.push_back(cp.ball = ballAround(cp.piece.vertices, tol));
    out.cellTrees[c] = BallTree(balls, tol);
  }
  for (PatchPlacement::CellPiece& b : out.slivers)
    b.piece.ball = ballAround(b.piece.piece.vertices, tol);
  if (!out.slivers.empty()) placeBeyondAirFragments(scene, tol, out);
  return out;
}

/// Per-thread state of the patch-level search. Beyond the stabbing test it prunes a branch when
/// every cell the branch might still reach (MightSee) holds only patches already seen in every
/// way they can be seen: the search's only output is those flags, so nothing is lost.
class PatchSearch {
 public:
  DeadlineCheck checkDeadline;
  PatchSearch(const Subdivision& sub, const PatchPlacement& placed, const PortalReach& might,
              const std::vector<CellSet>& cellReach, const Scene& scene, const Tolerance& tol)
      : sub_(sub),
        cellPatches_(placed.cellPatches),
        placements_(placed.placements),
        cellTrees_(placed.cellTrees),
        might_(might),
        cellReach_(cellReach),
        stabber_(tol),
        flags_(placed.placements.size(), 0),
        onPath_(sub.cells.size(), 0),
        partPieces_(sub.cells.size()),
        unsaturatedCount_(sub.cells.size(), 0),
        unsaturated_(sub.cells.size()),
        fullyMarked_(sub.cells.size()),
        scene_(scene),
        slivers_(placed.slivers, sub.cells.size(), placed.placements.size()),
        fragments_(placed.fragments, sub.cells.size(), placed.placements.size()),
        outsideTargets_(sub.cells.size()),
        tol_(tol) {
    size_t maxParts = 0;
    for (uint32_t c = 0; c < sub.cells.size(); ++c) {
      const size_t parts = sub.cells[c].parts.size();
      maxParts = std::max(maxParts, parts);
      if (parts == 0) continue;
      partPieces_[c].resize(parts);
      for (uint32_t k = 0; k < cellPatches_[c].size(); ++k)
        if (cellPatches_[c][k].part >= 0)
          partPieces_[c][static_cast<size_t>(cellPatches_[c][k].part)].push_back(k);
    }
    partOnPath_.assign(maxParts, 0);
    for (uint32_t c = 0; c < sub.cells.size(); ++c) {
      baseCount_.push_back(static_cast<uint32_t>(cellPatches_[c].size()));
      if (!cellPatches_[c].empty()) unsaturated_.insert(c);
    }
    unsaturatedCount_ = baseCount_;
    // One bit per piece, cell by cell in each cell tree's order (BallTree::order), set while
    // the piece is unsaturated: the over-budget answer skips a group of pieces with none set.
    std::vector<std::vector<uint32_t>> bitOf(sub.cells.size());
    for (uint32_t c = 0; c < sub.cells.size(); ++c) {
      bitBase_.push_back(pieceBits_);
      const std::span<const uint32_t> order = cellTrees_[c].order();
      bitOf[c].resize(order.size());
      for (uint32_t pos = 0; pos < order.size(); ++pos) bitOf[c][order[pos]] = pieceBits_ + pos;
      pieceBits_ += static_cast<uint32_t>(order.size());
    }
    unsaturatedPieces_.assign((pieceBits_ + 63) / 64, 0);
    for (uint32_t c = 0; c < sub.cells.size(); ++c) resetPieceBits(c);
    // Per patch, its pieces' cells and the flags that saturate each, side by side: mark() reads
    // them for every flag it sets, and reading the pieces themselves instead (scattered, large)
    // was a sixth of the patch stage on doom-fd1-e3m4.
    needsBegin_.reserve(placements_.size() + 1);
    for (const auto& where : placements_) {
      needsBegin_.push_back(static_cast<uint32_t>(needs_.size()));
      for (auto [cell, k] : where)
        needs_.push_back({cell, bitOf[cell][k], attainable(cellPatches_[cell][k])});
    }
    needsBegin_.push_back(static_cast<uint32_t>(needs_.size()));
  }

  PatchSearchResult run(uint32_t s) {
    PatchSearchResult result;
    stabber_.resetStats();
    facingRuleTests_ = 0;
    source_ = s;
    overBudget_ = false;
    // The source's own pieces are never targets: they count as saturated.
    for (uint32_t i = needsBegin_[s]; i < needsBegin_[s + 1]; ++i) saturate(needs_[i]);
    for (auto [cell, k] : placements_[s]) searchFrom(cell, cellPatches_[cell][k], result);
    // Then, on what is left of the run's budget, S's slivers into the outside, each looking
    // only for the fragments of fronts looking beyond the air (a ray that slipped through a
    // wall into the outside meets only backs or such fronts first), and S's fragments, each
    // looking only for slivers; either only for patches S can face and has not seen front.
    for (const bool fromSlivers : {true, false}) {
      const OutsidePieces& mine = fromSlivers ? slivers_ : fragments_;
      if (mine.of[s].empty()) continue;
      outside_ = fromSlivers ? &fragments_ : &slivers_;
      if (gatherOutsideTargets(s))
        for (uint32_t i : mine.of[s]) {
          outsideSource_ = &mine.pieces[i];
          searchFrom(mine.pieces[i].cell, mine.pieces[i].piece, result);
        }
      outside_ = nullptr;
      outsideSource_ = nullptr;
    }
    result.overBudget = overBudget_;
    for (uint32_t c : markedCells_) fullyMarked_.erase(c);
    markedCells_.clear();
    // From a patch moved onto a tilted plane, "seen" stands for "seen front to front" too: the
    // cells around its own plane do not tell its front from its back well enough for the front
    // flag to be trusted, and the blocker stage keeps only pairs seen front to front from both
    // ends (lq_e4m4: 22 of 10^6 `verify` rays met unlisted pairs; the 7 pairs printed all had
    // one ramp face, whose search saw its partners only from behind while they saw it front
    // to front). The other end's search and the blocker test still decide the pair.
    const bool tilted = std::any_of(placements_[s].begin(), placements_[s].end(), [&](auto pk) {
      return cellPatches_[pk.first][pk.second].tilted;
    });
    for (uint32_t t : touched_) {
      const uint8_t f = flags_[t];
      result.seen.push_back(seenEntry(t, tilted && (f & kSeen) ? f | kSeenFront : f));
      flags_[t] = 0;
    }
    touched_.clear();
    for (uint32_t c : touchedCells_) {
      unsaturatedCount_[c] = baseCount_[c];
      if (baseCount_[c] > 0) unsaturated_.insert(c);
      resetPieceBits(c);
    }
    touchedCells_.clear();
    std::sort(result.seen.begin(), result.seen.end());
    std::sort(result.sameCellVisible.begin(), result.sameCellVisible.end());
    result.sameCellVisible.erase(
        std::unique(result.sameCellVisible.begin(), result.sameCellVisible.end()),
        result.sameCellVisible.end());
    result.stabbing = stabber_.stats();
    result.facingRuleTests = facingRuleTests_;
    return result;
  }

  /// The search from `cp`, a piece of the run's source S in `cell`, whose front looks into it.
  void searchFrom(uint32_t cell, const CellPatch& cp, PatchSearchResult& result) {
    if (!cp.facesIn && !cp.interior) return;  // S's front does not look into this cell
    stabber_.clear();
    if (stabber_.push(cp.piece.vertices) == StabbingResult::Blocked) return;  // degenerate
    sourcePiece_ = &cp.piece;
    // The shortcut needs a convex cell with nothing inside (a cell of parts is not convex),
    // and S and T not on one boundary plane: the lines between those run within the plane's
    // slack, where pieces merged onto the plane, tilted within it, can stand in the way (such
    // pairs go to the blocker test). Pieces searched from both sides (`interior`: a patch whose
    // facing the BSP and the centroid disagree on) stay out of it too.
    const bool cellEmpty =
        sub_.cells[cell].interiorPatches.empty() && sub_.cells[cell].parts.empty();
    if (cp.whole && !cp.interior && cellEmpty) {
      for (const CellPatch& t : cellPatches_[cell])
        if (t.patch != source_ && t.whole && t.facesIn && !t.interior &&
            (t.boundaryPlane < 0 || t.boundaryPlane != cp.boundaryPlane))
          result.sameCellVisible.push_back(t.patch);
    }
    // A sightline from S is one from S's cell: it reaches only cells the cell search reached.
    const CellSet* reach = cellReach_.empty() ? nullptr : &cellReach_[cell];
    if (outside_ && exhausted()) {
      // A sliver or fragment after S's other pieces spent the run's budget (the usual case):
      // every piece it looks for in the cells its cell reaches. Walking the outside's openings
      // instead took doom-fd2-map03's patch stage from 3.6 to 6.0 s.
      outsideTargets_.forEach([&](size_t c) {
        if (!reach || reach->contains(c)) markWhatTheSequenceMayMeet(static_cast<uint32_t>(c));
      });
      return;
    }
    // Other pieces in merged cells (a patch's piece facing into a leaf by its centroid, one
    // placed across an opening) are searched from the whole cell: walked leaf by leaf they
    // ran over the search budget more often, and the budget's answer, every cell any opening
    // of the merged cell leads to, listed more (e3m4 +2.2 % pairs, base1-test +0.1 %).
    if (cp.sliver && cp.part >= 0) {
      visitPart(cell, static_cast<uint32_t>(cp.part), 0, reach);
    } else {
      visit(cell, 0, reach);
    }
  }

  /// Stabbing tests (portals and targets) one run may make (0: no limit). Past it the search
  /// stops testing: every branch it has not explored yet is answered with every piece, with
  /// every flag, in every cell the branch might reach (its reach set), which is conservative —
  /// the branch's stabbable sequences reach only those cells — and keeps the exact answers of
  /// the branches already explored.
  void setBudget(uint64_t tests) { budget_ = tests ? tests : UINT64_MAX; }
  /// PropagationOptions::patchBudgetAnswerByPlanes.
  void setBudgetAnswerByPlanes(bool on) { budgetAnswerByPlanes_ = on; }

 private:
  struct Need {
    uint32_t cell;
    uint32_t bit;   // the piece's bit in unsaturatedPieces_
    uint8_t flags;  // attainable() of the piece there
  };
  bool exhausted() {
    if (!overBudget_ && stabber_.stats().tests >= budget_) overBudget_ = true;
    return overBudget_;
  }

  /// Marks every piece of `cell` (but the source's) with every flag it could get.
  void markCell(uint32_t cell) {
    if (outside_) {
      if (!outsideTargets_.contains(cell)) return;
      for (uint32_t i : outside_->in[cell]) {
        const CellPatch& t = outside_->pieces[i].piece;
        if (t.patch != source_ && mayMeetAcross(outside_->pieces[i])) mark(t.patch, attainable(t));
      }
      return;
    }
    if (fullyMarked_.contains(cell)) return;
    fullyMarked_.insert(cell);
    markedCells_.push_back(cell);
    for (const CellPatch& t : cellPatches_[cell])
      if (t.patch != source_) mark(t.patch, attainable(t));
  }

  /// Over the budget: marks the pieces of `cell` a line of the current sequence may still meet
  /// (PortalSequenceStabber::mayCrossLater: not wholly behind the first piece's plane, the last
  /// portal's or a separating plane of the two, with the clips' slack), each with every flag
  /// it could get. The cell's ball tree rejects groups of pieces by one test of their ball,
  /// then each piece of a group kept is tested. A piece left out would be clipped away by the
  /// same planes if the branch were explored: conservative.
  /// Marking every piece of every cell the branch might reach instead listed 1.47 times the
  /// pairs on doom-fd2-map10 (nearly every search runs over its budget there) and 1.09 times
  /// on q3-oacmpdm1.
  void markWhatTheSequenceMayMeet(uint32_t cell) {
    if (!budgetAnswerByPlanes_) {
      markCell(cell);
      return;
    }
    if (outside_) {
      // From a sliver or a fragment: the few pieces it looks for, one by one. (S's own are
      // skipped: marking S would saturate its pieces a second time.)
      if (!outsideTargets_.contains(cell)) return;
      const LaterPlanes planes{stabber_.laterPlanes()};
      for (uint32_t i : outside_->in[cell]) {
        const CellPatch& t = outside_->pieces[i].piece;
        const uint8_t f = attainable(t);
        uint64_t mask = planes.all();
        if (t.patch != source_ && (flags_[t.patch] & f) != f &&
            mayMeetAcross(outside_->pieces[i]) &&
            planes.keep(t.ball.center, t.ball.radius, t.piece.vertices, mask))
          mark(t.patch, f);
      }
      return;
    }
    if (!unsaturated_.contains(cell)) return;
    const std::vector<CellPatch>& pieces = cellPatches_[cell];
    const LaterPlanes planes{stabber_.laterPlanes()};
    const uint32_t base = bitBase_[cell];
    cellTrees_[cell].forEachKept(
        planes.all(),
        [&](const Ball& b, BallTree::ItemRange range, uint64_t& mask) {
          return anyPieceUnsaturated(base + range.begin, base + range.end) &&
                 planes.keep(b.center, b.radius, {}, mask);
        },
        [&](uint32_t k, uint64_t mask) {
          const CellPatch& t = pieces[k];
          if (t.patch == source_) return;
          const uint8_t f = attainable(t);
          if ((flags_[t.patch] & f) == f) return;
          if (planes.keep(t.ball.center, t.ball.radius, t.piece.vertices, mask)) mark(t.patch, f);
        });
  }

  /// A piece now has every flag it can get: nothing more is looked for in it.
  void saturate(const Need& piece) {
    unsaturatedPieces_[piece.bit >> 6] &= ~(uint64_t{1} << (piece.bit & 63));
    decrement(piece.cell);
  }

  /// The cells where the current outside search of S looks (outsideTargets_): those of the
  /// pieces it looks for (outside_) of patches S can face and has not seen front yet. False
  /// when there are none.
  bool gatherOutsideTargets(uint32_t s) {
    outsideTargets_.clear();
    const ConvexPolygon& sp = scene_.patches[s].polygon;
    bool any = false;
    for (const PatchPlacement::CellPiece& t : outside_->pieces) {
      const uint32_t p = t.piece.patch;
      if (p == s || (flags_[p] & kSeenFront) || outsideTargets_.contains(t.cell) ||
          !canFace(sp, scene_.patches[p].polygon, tol_.length()))
        continue;
      outsideTargets_.insert(t.cell);
      any = true;
    }
    return any;
  }

  /// In an outside search, whether `target` may be met by a ray between it and the piece the
  /// search is from (outsideSource_). One of the pair is a sliver of a patch S, and such a ray
  /// leaves S's front and crosses one of the sliver's walls (CellPiece::crossed) within the
  /// slack of its start: it goes on in front of both planes, from near where they meet, so the
  /// other piece has a part in front of both.
  bool mayMeetAcross(const PatchPlacement::CellPiece& target) const {
    const PatchPlacement::CellPiece& from = *outsideSource_;
    const bool fromSliver = !from.crossed.empty();
    const PatchPlacement::CellPiece& sliver = fromSliver ? from : target;
    if (sliver.crossed.empty()) return true;
    const double slack = tol_.planeOffset();
    auto grown = [&](const Plane& h) { return Plane{h.normal, h.offset - slack}; };
    const std::optional<ConvexPolygon> ahead =
        clipToFront((fromSliver ? target : from).piece.piece,
                    grown(scene_.patches[sliver.piece.patch].polygon.plane), tol_);
    if (!ahead) return false;
    return std::any_of(sliver.crossed.begin(), sliver.crossed.end(), [&](const Plane& w) {
      return std::any_of(ahead->vertices.begin(), ahead->vertices.end(),
                         [&](const Vec3& v) { return w.distance(v) > -slack; });
    });
  }

  /// Sets the bits of every piece of `cell` again (after a run).
  void resetPieceBits(uint32_t cell) {
    const uint32_t end = bitBase_[cell] + static_cast<uint32_t>(cellPatches_[cell].size());
    for (uint32_t b = bitBase_[cell]; b < end; ++b)
      unsaturatedPieces_[b >> 6] |= uint64_t{1} << (b & 63);
  }

  /// Is a bit in [begin, end) set: a piece there still unsaturated?
  bool anyPieceUnsaturated(uint32_t begin, uint32_t end) const {
    if (begin >= end) return false;
    const uint32_t first = begin >> 6, last = (end - 1) >> 6;
    const uint64_t head = ~uint64_t{0} << (begin & 63);
    const uint64_t tail = ~uint64_t{0} >> (63 - ((end - 1) & 63));
    if (first == last) return (unsaturatedPieces_[first] & head & tail) != 0;
    if (unsaturatedPieces_[first] & head) return true;
    for (uint32_t w = first + 1; w < last; ++w)
      if (unsaturatedPieces_[w]) return true;
    return (unsaturatedPieces_[last] & tail) != 0;
  }

  void decrement(uint32_t cell) {
    if (unsaturatedCount_[cell] == baseCount_[cell]) touchedCells_.push_back(cell);
    if (--unsaturatedCount_[cell] == 0) unsaturated_.erase(cell);
  }

  void mark(uint32_t t, uint8_t f) {
    const uint8_t before = flags_[t];
    const uint8_t after = before | f;
    if (after == before) return;
    if (before == 0) touched_.push_back(t);
    flags_[t] = after;
    for (uint32_t i = needsBegin_[t]; i < needsBegin_[t + 1]; ++i) {
      const uint8_t need = needs_[i].flags;
      if ((before & need) != need && (after & need) == need) saturate(needs_[i]);
    }
  }

  /// The sequence (S's piece, T's piece) inside one convex cell, decided exactly by
  /// facingLines (facing_lines.h) instead of the stabbing kernel.
  void testInSourceCell(const CellPatch& t) {
    const uint8_t have = flags_[t.patch];
    const bool wantFront = (t.facesIn || t.interior) && !(have & kSeenFront);
    const bool wantBack = (!t.facesIn || t.interior) && !(have & kSeen);
    if (!wantFront && !wantBack) return;
    const FacingLines lines = facingLines(*sourcePiece_, t.piece, tol_.length());
    if (wantFront) {
      ++facingRuleTests_;
      if (lines.throughFront) mark(t.patch, kSeen | kSeenFront);
    }
    if (wantBack && !(flags_[t.patch] & kSeen)) {
      ++facingRuleTests_;
      if (lines.throughBack) mark(t.patch, kSeen);
    }
  }

  /// Tests T crossed the way a sightline arriving from inside the cell crosses it.
  void testTarget(const CellPatch& t) {
    if (t.patch == source_) return;
    if (stabber_.depth() == 1) {
      testInSourceCell(t);
      return;
    }
    const uint8_t have = flags_[t.patch];
    // Front hit: the line crosses T from its front to its back (loop reversed = travel normal).
    if ((t.facesIn || t.interior) && !(have & kSeenFront)) {
      scratch_.assign(t.piece.vertices.rbegin(), t.piece.vertices.rend());
      if (stabber_.push(scratch_) != StabbingResult::Blocked) {
        mark(t.patch, kSeen | kSeenFront);
        stabber_.pop();
      }
    }
    if ((!t.facesIn || t.interior) && !(flags_[t.patch] & kSeen)) {
      if (stabber_.push(t.piece.vertices) != StabbingResult::Blocked) {
        mark(t.patch, kSeen);
        stabber_.pop();
      }
    }
  }

  /// Tests the pieces the current search looks for in `cell` (only leaf `part` of it when
  /// part >= 0): its own pieces, or in an outside search (outside_) the slivers or fragments.
  void testTargets(uint32_t cell, int32_t part) {
    if (outside_) {
      if (!outsideTargets_.contains(cell)) return;
      for (uint32_t i : outside_->in[cell]) {
        const CellPatch& t = outside_->pieces[i].piece;
        if ((part < 0 || t.part == part) && mayMeetAcross(outside_->pieces[i])) testTarget(t);
      }
      return;
    }
    if (part < 0) {
      for (const CellPatch& t : cellPatches_[cell]) testTarget(t);
    } else {
      for (uint32_t k : partPieces_[cell][static_cast<size_t>(part)])
        testTarget(cellPatches_[cell][k]);
    }
  }

  /// `reach`: the cells this branch may still reach (null: all).
  void visit(uint32_t cell, size_t depth, const CellSet* reach) {
    checkDeadline();
    onPath_[cell] = 1;
    if (exhausted()) {
      markWhatTheSequenceMayMeet(cell);
    } else {
      testTargets(cell, -1);
    }
    for (uint32_t pid : sub_.cells[cell].portals) leaveThrough(cell, pid, depth, reach);
    onPath_[cell] = 0;
  }

  /// One branch of a search at `depth`: out of `cell` through portal `pid`, on into the cell
  /// beyond. `reach`: the cells this branch may still reach (null: all).
  void leaveThrough(uint32_t cell, uint32_t pid, size_t depth, const CellSet* reach) {
    const Portal& p = sub_.portals[pid];
    const uint32_t next = p.other(cell);
    // A line cannot enter a convex cell twice; one that leaves a merged cell and comes back
    // also takes the shorter sequence without the loop (convex_merge.h).
    if (onPath_[next]) return;
    const bool forward = p.front == next;
    const CellSet& through = might_.through(pid, forward);
    if (stack_.size() <= depth) stack_.resize(depth + 1);
    CellSet& nextReach = stack_[depth];
    if (reach) nextReach.assignIntersection(*reach, through);
    const CellSet& r = reach ? nextReach : through;
    // Nothing new can be seen that way (an outside search looks only where its targets are).
    if (!r.intersects(outside_ ? outsideTargets_ : unsaturated_)) return;
    // Over the budget the portal is still tested (one test per branch left on the path: a
    // bounded number), and a branch that passes is answered without exploring it: the pieces
    // a line through it may meet in every cell it might reach.
    if (!pushDirected(p.polygon, forward)) return;
    if (exhausted()) {
      markWhatTheSequenceMayMeet(next);
      r.forEach([&](size_t c) { markWhatTheSequenceMayMeet(static_cast<uint32_t>(c)); });
    } else {
      visit(next, depth + 1, &r);
    }
    stabber_.pop();
  }

  /// The search from a sliver of S (placeThinWallSlivers) in one leaf (`part`) of a merged
  /// cell. Searched from the whole cell, a piece sees through every opening of the cell as if
  /// the cell were convex, which on a real level is its whole outside (convex_merge.h). So the
  /// leaves are walked one by one through the cell's inner openings, each pushed as a
  /// portal (a line meets a convex leaf in one segment, so it crosses the openings between the
  /// leaves it passes in order): in each leaf its own pieces are tested, and the cell is left
  /// through the openings on that leaf's boundary. The cell itself stays off the path: a line
  /// may leave it and come back into another leaf, and that return is followed as any search
  /// enters a merged cell, whole. Measured on doom-fd2-map01 with `--outside-slivers`: 604,691
  /// pairs against 607,592 from the whole cell, most searches running over the budget either
  /// way; 563,171 with the budget at 10^5 tests (with a looser over-budget answer than below).
  void visitPart(uint32_t cell, uint32_t part, size_t depth, const CellSet* reach) {
    checkDeadline();
    const Cell& c = sub_.cells[cell];
    if (exhausted()) {
      // Over the budget: what a search from the whole cell answers then (visit): every piece of
      // the cell, and through each opening of the cell a line of the sequence passes, every
      // cell the opening might lead to (a bounded number of tests, whatever leaves the line
      // passes in between).
      markCell(cell);
      for (uint32_t pid : c.portals) leaveThrough(cell, pid, depth, reach);
      return;
    }
    partOnPath_[part] = 1;
    testTargets(cell, static_cast<int32_t>(part));
    const CellPart& leaf = c.parts[part];
    for (uint32_t pid : leaf.portals) leaveThrough(cell, pid, depth, reach);
    for (uint32_t ip : leaf.innerPortals) {
      const InnerPortal& p = c.innerPortals[ip];
      const uint32_t next = p.other(part);
      if (partOnPath_[next]) continue;
      if (!pushDirected(p.polygon, p.front == next)) continue;
      visitPart(cell, next, depth + 1, reach);
      stabber_.pop();
    }
    partOnPath_[part] = 0;
  }

  /// Pushes `polygon` crossed towards its front (`forward`) or its back; false when the sequence
  /// is then blocked (nothing pushed).
  bool pushDirected(const ConvexPolygon& polygon, bool forward) {
    if (forward) {
      scratch_ = polygon.vertices;
    } else {
      scratch_.assign(polygon.vertices.rbegin(), polygon.vertices.rend());
    }
    return stabber_.push(scratch_) != StabbingResult::Blocked;
  }

  const Subdivision& sub_;
  const std::vector<std::vector<CellPatch>>& cellPatches_;
  const Placements& placements_;
  const std::vector<BallTree>& cellTrees_;
  const PortalReach& might_;
  const std::vector<CellSet>& cellReach_;  // per cell, the cells it may see (empty: unknown)
  PortalSequenceStabber stabber_;
  std::vector<uint8_t> flags_;
  std::vector<Need> needs_;           // per patch, its pieces in placements_'s order
  std::vector<uint32_t> needsBegin_;  // patch t's run: needs_[needsBegin_[t], needsBegin_[t+1])
  std::vector<uint32_t> touched_, touchedCells_;
  std::vector<uint8_t> onPath_;
  // Per merged cell and leaf, the indices of the leaf's pieces in cellPatches_[cell].
  std::vector<std::vector<std::vector<uint32_t>>> partPieces_;
  std::vector<uint8_t> partOnPath_;  // the leaves on the path of visitPart's walk
  std::vector<uint32_t> baseCount_, unsaturatedCount_;
  // A bit per piece, set while it is unsaturated (cell c's pieces from bitBase_[c] on, in its
  // tree's order), for the over-budget answer's walk (markWhatTheSequenceMayMeet).
  std::vector<uint64_t> unsaturatedPieces_;
  std::vector<uint32_t> bitBase_;
  uint32_t pieceBits_ = 0;
  CellSet unsaturated_;
  std::deque<CellSet> stack_;  // deque: growing it keeps references to its elements valid
  std::vector<Vec3> scratch_;
  uint32_t source_ = 0;
  const ConvexPolygon* sourcePiece_ = nullptr;  // S's piece that starts the current sequence
  uint64_t facingRuleTests_ = 0;
  uint64_t budget_ = UINT64_MAX;  // stabbing tests per run (setBudget)
  bool budgetAnswerByPlanes_ = true;
  bool overBudget_ = false;
  CellSet fullyMarked_;                // cells markCell has done in this run
  std::vector<uint32_t> markedCells_;  // the same, listed (to clear them)
  const Scene& scene_;
  /// PatchPlacement::slivers or ::fragments, indexed by cell and by patch.
  struct OutsidePieces {
    OutsidePieces(const std::vector<PatchPlacement::CellPiece>& all, size_t cells, size_t patches)
        : pieces(all), in(cells), of(patches) {
      for (uint32_t i = 0; i < all.size(); ++i) {
        in[all[i].cell].push_back(i);
        of[all[i].piece.patch].push_back(i);
      }
    }
    const std::vector<PatchPlacement::CellPiece>& pieces;
    std::vector<std::vector<uint32_t>> in, of;
  };
  const OutsidePieces slivers_, fragments_;
  const OutsidePieces* outside_ = nullptr;  // what the current outside search looks for
  const PatchPlacement::CellPiece* outsideSource_ = nullptr;  // and the piece it is from
  CellSet outsideTargets_;  // and the cells where (gatherOutsideTargets)
  Tolerance tol_;
};

}  // namespace

std::vector<std::vector<uint32_t>> frontCellsOfPatches(const Scene& scene, const Subdivision& sub,
                                                       bool outsideSlivers) {
  const PatchPlacement placed = placePatches(scene, sub, sub.tree.tol, outsideSlivers);
  std::vector<std::vector<uint32_t>> cells(scene.patches.size());
  for (size_t p = 0; p < cells.size(); ++p) {
    for (const auto& [cell, piece] : placed.placements[p]) {
      const CellPatch& cp = placed.cellPatches[cell][piece];
      // As PatchSearch::run starts from, and as it flags kSeenFront: the front's cells only.
      // (Not the beyond-air slivers, which are not placements: light through a gap the width
      // of the contact distance carries no measurable power.)
      if (cp.facesIn || cp.interior) cells[p].push_back(cell);
    }
    std::sort(cells[p].begin(), cells[p].end());
    cells[p].erase(std::unique(cells[p].begin(), cells[p].end()), cells[p].end());
  }
  return cells;
}

std::vector<PatchSearchResult> searchPatches(const Scene& scene, const Subdivision& sub,
                                             const CellVisibility& cells, int threads,
                                             const PropagationOptions& options,
                                             VisibilityStats& st) {
  const size_t n = scene.patches.size();
  const Tolerance tol = sub.tree.tol;
  const PatchPlacement placed = placePatches(scene, sub, tol, options.outsideSlivers);
  st.thinWallSlivers = placed.thinWallSlivers;
  st.beyondAirSlivers = placed.slivers.size();
  st.beyondAirFragments = placed.fragments.size();
  st.acrossPortalPieces = placed.acrossPortals;
  st.acrossThinSlabPieces = placed.acrossThinSlabs;
  const PortalReach reach = cells.reach();
  const std::vector<CellSet>& cellReach = cells.cellReach;
  std::vector<PatchSearchResult> seen(n);
  st.patchBudget = patchSequenceBudgetFor(options.patchSequenceBudget, n);
  std::atomic<size_t> done{0};
  std::mutex progressMutex;
  parallelFor(
      n, threads,
      [&] {
        PatchSearch w(sub, placed, reach, cellReach, scene, tol);
        w.checkDeadline.deadline = options.deadline;
        w.setBudget(st.patchBudget);
        w.setBudgetAnswerByPlanes(options.patchBudgetAnswerByPlanes);
        return w;
      },
      [&](PatchSearch& w, size_t s) {
        seen[s] = w.run(static_cast<uint32_t>(s));
        const size_t d = ++done;
        if (options.progress && (d % 64 == 0 || d == n)) {
          std::lock_guard lock(progressMutex);
          options.progress(d, n);
        }
      });
  StabbingStats stabbing;
  uint64_t seenEntries = 0;
  for (const PatchSearchResult& r : seen) {
    stabbing += r.stabbing;
    st.patchFacingRuleTests += r.facingRuleTests;
    seenEntries += r.seen.size();
    st.patchSearchesOverBudget += r.overBudget;
  }
  st.meanPatchesSeen = n ? double(seenEntries) / double(n) : 0;
  st.patchStabbingTests = stabbing.tests + st.patchFacingRuleTests;
  st.patchStabbing = stabbing;
  st.unresolvedStabbing = stabbing.unresolved + stabbing.lpNumericalFailures;
  return seen;
}

}  // namespace gv
