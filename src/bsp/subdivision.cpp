// Building the subdivision (BSP, then portals) and its §7.1 statistics. Paper §3, §7.1.
#include "bsp/subdivision.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include "bsp/portals.h"
#include "util/timing.h"

namespace gv {
namespace {

void sortUnique(std::vector<uint32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

std::vector<uint32_t> Subdivision::neighbours(uint32_t cell) const {
  std::vector<uint32_t> out;
  for (uint32_t p : cells[cell].portals) out.push_back(portals[p].other(cell));
  sortUnique(out);
  return out;
}

bool somePatchFacesInto(const Scene& scene, const Cell& cell) {
  if (!cell.interiorPatches.empty() || !cell.facingPatches.empty()) return true;
  const Vec3 inside = cell.shape.centroid();
  return std::any_of(cell.patches.begin(), cell.patches.end(), [&](uint32_t p) {
    return scene.patches[p].polygon.plane.distance(inside) > 0;
  });
}

Subdivision buildSubdivision(const Scene& scene, const BspOptions& options) {
  Subdivision sub;
  const auto bspStart = Clock::now();
  sub.tree = buildBspTree(scene, options);
  sub.stats.bspSeconds = secondsSince(bspStart);

  const auto portalStart = Clock::now();
  sub.cells.resize(sub.tree.leaves.size());
  for (size_t i = 0; i < sub.cells.size(); ++i) {
    const BspLeaf& leaf = sub.tree.leaves[i];
    Cell& cell = sub.cells[i];
    cell.shape = leaf.shape;
    cell.faces.resize(leaf.shape.faces.size());
    for (const PatchFragment& f : leaf.interior) cell.interiorPatches.push_back(f.patch);
    sortUnique(cell.interiorPatches);
  }
  buildPortals(sub);

  size_t faces = 0, coaffine = 0;
  for (Cell& cell : sub.cells) {
    std::vector<uint32_t> onBoundary;
    for (size_t i = 0; i < cell.faces.size(); ++i) {
      const BoundaryFace& face = cell.faces[i];
      onBoundary.insert(onBoundary.end(), face.coaffinePatches.begin(), face.coaffinePatches.end());
      const Vec3 outward = cell.shape.faces[i].polygon.plane.normal;
      for (uint32_t p : face.coaffinePatches)
        if (dot(outward, scene.patches[p].polygon.plane.normal) < 0)
          cell.facingPatches.push_back(p);
    }
    sortUnique(cell.facingPatches);
    sortUnique(onBoundary);
    coaffine += onBoundary.size();
    faces += cell.faces.size();
    cell.patches = onBoundary;
    cell.patches.insert(cell.patches.end(), cell.interiorPatches.begin(),
                        cell.interiorPatches.end());
    sortUnique(cell.patches);
  }
  sub.stats.portalSeconds = secondsSince(portalStart);

  SubdivisionStats& s = sub.stats;
  s.patches = scene.patches.size();
  s.planes = sub.tree.planes.planes().size();
  s.nodes = sub.tree.nodes.size();
  s.cells = sub.cells.size();
  s.portals = sub.portals.size();
  s.depth = sub.tree.depth;
  const double n = static_cast<double>(std::max<size_t>(1, s.cells));
  s.meanFacesPerCell = static_cast<double>(faces) / n;
  s.meanCoaffinePatchesPerCell = static_cast<double>(coaffine) / n;
  s.meanPortalsPerCell = 2.0 * static_cast<double>(s.portals) / n;
  s.minCoverage = options.minCoverage;
  std::vector<char> interior(scene.patches.size(), 0);
  for (const Cell& cell : sub.cells)
    for (uint32_t p : cell.interiorPatches) interior[p] = 1;
  double inside = 0, total = 0;
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const double area = scene.patches[p].polygon.area();
    total += area;
    if (interior[p]) inside += area;
  }
  s.interiorAreaFraction = total > 0 ? inside / total : 0;
  std::vector<char> blind(sub.cells.size());
  size_t sealed = 0, blindPortals = 0;
  for (size_t c = 0; c < sub.cells.size(); ++c) {
    blind[c] = !somePatchFacesInto(scene, sub.cells[c]);
    sealed += sub.cells[c].portals.empty();
  }
  for (const Portal& p : sub.portals) blindPortals += blind[p.back] || blind[p.front];
  s.sealedCellFraction = double(sealed) / double(std::max<size_t>(1, sub.cells.size()));
  s.blindPortalFraction = double(blindPortals) / double(std::max<size_t>(1, sub.portals.size()));
  return sub;
}

bool builtOfClosedSolids(const SubdivisionStats& s) {
  return s.sealedCellFraction >= kClosedSolidsMinSealedCells &&
         s.blindPortalFraction <= kClosedSolidsMaxBlindPortals;
}

Subdivision buildVisibilitySubdivision(const Scene& scene, BspOptions options) {
  std::optional<Subdivision> kept;
  bool closedSolidsDetail = false;  // kept unless the next rule takes most of its inside area
  for (double coverage : kVisibilityCoverageSteps) {
    options.minCoverage = coverage;
    Subdivision sub = buildSubdivision(scene, options);
    if (kept && kept->stats.interiorAreaFraction <= kShatterInteriorAreaFraction &&
        double(sub.stats.portals) > kMaxPortalsPerPatch * double(sub.stats.patches))
      break;
    if (closedSolidsDetail && sub.stats.interiorAreaFraction * kClosedSolidsMinInteriorReduction >
                                  kept->stats.interiorAreaFraction)
      break;
    kept = std::move(sub);
    const SubdivisionStats& s = kept->stats;
    if (s.interiorAreaFraction <= kMaxInteriorAreaFraction) break;
    closedSolidsDetail = coverage < kVisibilityCoverageSteps[0] &&
                         s.interiorAreaFraction <= kClosedSolidsMaxInteriorAreaFraction &&
                         builtOfClosedSolids(s);
  }
  return std::move(*kept);
}

}  // namespace gv
