// Hidden faces and coincident twins, decided on the all-planes BSP (see hidden_faces.h).
//
// Why the cells decide: with every patch plane split on (minCoverage 0), every patch fragment
// lies on cell boundaries, so no patch crosses a cell's inside and the winding number, which
// jumps only across patches, is the same at every point of one cell. A fragment's front looks
// into exactly one cell; it is hidden when that cell is inside a solid. Light and sightlines
// from air never enter a solid's cell (they would cross the solid's own faces first), so what is
// removed is what the outside checks' photons and rays can never reach.
#include "bsp/hidden_faces.h"

#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "bsp/coplanar_clip.h"
#include "bsp/subdivision.h"
#include "scene/face_to_patches.h"

namespace gv {
namespace {

/// The fragment `p` clipped to the cell, without the cell's halfspaces that `p` lies on (those
/// would cut a patch lying on the cell's boundary at rounding depth).
std::optional<ConvexPolygon> pieceInCell(const ConvexPolygon& p, const ConvexPolyhedron& cell,
                                         const Tolerance& tol) {
  std::optional<ConvexPolygon> cur = p;
  for (const Plane& h : cell.halfspaces) {
    bool lies = true;
    for (const Vec3& v : cur->vertices)
      if (std::abs(h.distance(v)) > tol.planeOffset()) lies = false;
    if (lies) continue;
    cur = clipToFront(*cur, h.flipped(), tol);
    if (!cur) return std::nullopt;
  }
  return cur;
}

/// A patch's fragment whose front looks into one cell.
struct Piece {
  uint32_t patch = 0;
  ConvexPolygon polygon;
};

/// Which winding number is air, and so which regions no air reaches. In a soup of closed
/// outward-facing solids (brushes, boxes) air is 0 and a solid's inside +1; inside inward-facing
/// shells (a 2.5D sector level: floors, ceilings and walls facing into the sectors) air is -1
/// and 0 is the void outside every sector. A scene is taken for shells when more of the pieces'
/// area looks into cells near -1 than into cells near 0.
bool shellLevel(const std::vector<std::vector<Piece>>& pieces, const std::vector<double>& wind) {
  double shellArea = 0, openArea = 0;
  for (size_t c = 0; c < pieces.size(); ++c)
    for (const Piece& piece : pieces[c]) {
      if (wind[c] <= -0.5) {
        shellArea += piece.polygon.area();
      } else if (wind[c] < 0.5) {
        openArea += piece.polygon.area();
      }
    }
  return shellArea > openArea;
}

/// Per cell some piece looks into, whether no air reaches it: a closed solid's inside (the
/// hidden cells), and on a level of shells also the void (winding number above -1/2). Fractions
/// near open edges fall on the side of "beyond air" there: the flag only widens what `vis`
/// searches for.
std::vector<uint8_t> cellsBeyondAir(const std::vector<std::vector<Piece>>& pieces,
                                    const std::vector<double>& wind, bool shells) {
  std::vector<uint8_t> out(pieces.size(), 0);
  for (size_t c = 0; c < pieces.size(); ++c)
    if (!pieces[c].empty()) out[c] = wind[c] >= (shells ? -0.5 : kSolidWindingNumber);
  return out;
}

}  // namespace

Scene removeHiddenFaces(const Scene& scene, const HiddenFaceOptions& options,
                        HiddenFaceReport* report) {
  HiddenFaceReport rep;
  if (scene.patches.empty()) {
    if (report) *report = rep;
    return scene;
  }
  BspOptions bsp;
  bsp.minCoverage = 0;  // every plane: no patch crosses a cell, so each cell is in or out
  const Subdivision sub = buildSubdivision(scene, bsp);
  const Tolerance tol = sub.tree.tol;
  const size_t nCells = sub.cells.size();

  // The pieces whose front looks into each cell; a patch left inside a cell (a plane that only
  // grazed it) is kept whole: it is not decided here.
  std::vector<std::vector<Piece>> pieces(nCells);
  std::vector<uint8_t> undecided(scene.patches.size(), 0);
  for (const Cell& cell : sub.cells)
    for (uint32_t p : cell.interiorPatches) undecided[p] = 1;
  tbb::parallel_for(size_t{0}, nCells, [&](size_t c) {
    const Cell& cell = sub.cells[c];
    const Vec3 inside = cell.shape.centroid();
    for (uint32_t p : cell.patches) {
      if (std::binary_search(cell.interiorPatches.begin(), cell.interiorPatches.end(), p)) continue;
      const ConvexPolygon& poly = scene.patches[p].polygon;
      if (poly.plane.distance(inside) <= 0) continue;  // faces out of this cell
      if (auto piece = pieceInCell(poly, cell.shape, tol))
        pieces[c].push_back({p, std::move(*piece)});
    }
  });

  // Solid cells: only those some piece looks into matter.
  std::vector<uint8_t> solid(nCells, 0);
  std::vector<double> wind(nCells, 0);
  const WindingNumberField winding(scene);
  tbb::parallel_for(size_t{0}, nCells, [&](size_t c) {
    if (pieces[c].empty()) return;
    wind[c] = winding.at(sub.cells[c].shape.centroid());
    solid[c] = wind[c] >= kSolidWindingNumber;
  });
  rep.shells = shellLevel(pieces, wind);
  const std::vector<uint8_t> beyondAir = cellsBeyondAir(pieces, wind, rep.shells);

  // Per patch: its pieces in air, after the earlier same-facing patches on its plane in the same
  // cell took their overlap. `cut` marks a patch that lost anything.
  std::vector<std::vector<ConvexPolygon>> kept(scene.patches.size());
  std::vector<uint8_t> cutByHiding(scene.patches.size(), 0), cutByTwin(scene.patches.size(), 0);
  std::vector<uint8_t> hasPiece(scene.patches.size(), 0);
  std::vector<Aabb> beyond(scene.patches.size());  // the box of its pieces beyond air
  std::vector<std::vector<Aabb>> keptBeyond(scene.patches.size());  // per piece of kept[p]
  for (size_t c = 0; c < nCells; ++c) {
    std::vector<Piece>& here = pieces[c];
    std::sort(here.begin(), here.end(),
              [](const Piece& a, const Piece& b) { return a.patch < b.patch; });
    std::vector<const Piece*> earlier;  // the air pieces of this cell so far
    for (const Piece& piece : here) {
      hasPiece[piece.patch] = 1;
      if (beyondAir[c]) beyond[piece.patch].add(piece.polygon.bounds());
      if (solid[c]) {
        cutByHiding[piece.patch] = 1;
        continue;
      }
      const PatchPlane& pp = sub.tree.planes.of(piece.patch);
      std::vector<ConvexPolygon> rest{piece.polygon}, next;
      for (const Piece* e : earlier) {
        const PatchPlane& ep = sub.tree.planes.of(e->patch);
        if (ep.plane != pp.plane || ep.facesAlong != pp.facesAlong) continue;
        next.clear();
        for (ConvexPolygon& r : rest) {
          // Only a real overlap cuts: subtracting a neighbour that merely shares an edge would
          // still split `r` along the extensions of the neighbour's other edges.
          if (!intersectCoplanar(r, e->polygon, tol)) {
            next.push_back(std::move(r));
            continue;
          }
          subtractCoplanar(r, e->polygon, tol, next);
          cutByTwin[piece.patch] = 1;
        }
        std::swap(rest, next);
        if (rest.empty()) break;
      }
      for (ConvexPolygon& r : rest) {
        keptBeyond[piece.patch].push_back(beyondAir[c] ? r.bounds() : Aabb{});
        kept[piece.patch].push_back(std::move(r));
      }
      earlier.push_back(&piece);
    }
  }

  Scene out;
  out.materials = scene.materials;
  out.report = scene.report;
  // A patch kept whole keeps the box of all its pieces beyond air (undecided ones: none known);
  // a cut patch's pieces each their own.
  auto keep = [&](const Patch& patch, const Aabb& beyondAirBox) {
    out.patches.push_back(patch);
    out.beyondAirBounds.push_back(beyondAirBox);
  };
  for (uint32_t p = 0; p < scene.patches.size(); ++p) {
    const Patch& patch = scene.patches[p];
    const bool cut = cutByHiding[p] || cutByTwin[p];
    if (undecided[p] || !hasPiece[p] || !cut) {
      keep(patch, undecided[p] ? Aabb{} : beyond[p]);
      continue;
    }
    // Pieces the importer would drop: patches.obj must read back as these patches.
    for (size_t k = kept[p].size(); k-- > 0;) {
      if (!isSliver(kept[p][k], tol)) continue;
      kept[p].erase(kept[p].begin() + static_cast<std::ptrdiff_t>(k));
      keptBeyond[p].erase(keptBeyond[p].begin() + static_cast<std::ptrdiff_t>(k));
    }
    if (kept[p].empty()) {
      ++(cutByTwin[p] && !cutByHiding[p] ? rep.coincident : rep.hidden);
    } else if (!options.cutPartly) {
      // Kept whole: its hidden part is unreachable by light and rays alike, so it only lowers
      // the patch's mean the same way for the solver and a tracer on patches.obj, and cutting
      // along the all-planes BSP would shatter it into many pieces.
      keep(patch, beyond[p]);
      ++rep.partlyKept;
    } else {
      ++(cutByHiding[p] ? rep.partlyHidden : rep.partlyCoincident);
      for (size_t k = 0; k < kept[p].size(); ++k) {
        keep({std::move(kept[p][k]), patch.material, patch.sourceFace}, keptBeyond[p][k]);
        ++rep.piecesOut;
      }
    }
  }
  rep.frontBeyondAir =
      static_cast<size_t>(std::count_if(out.beyondAirBounds.begin(), out.beyondAirBounds.end(),
                                        [](const Aabb& b) { return !b.empty(); }));
  if (report) *report = rep;
  return out;
}

}  // namespace gv
