// Merging cells (see convex_merge.h for why nothing visible is lost).
//
// The convexity test. Let X and Y be convex with disjoint interiors, touching in a face on plane
// P, X behind P and Y in front. Write X = X' ∩ P⁻ and Y = Y' ∩ P⁺, where X' (Y') is the
// intersection of X's (Y's) other halfspaces. If some vertex y of Y lies outside a halfspace h of
// X' (h not on P), take a point x inside X's face on h: it lies strictly behind P, and the segment
// from x towards y leaves X at once (it crosses h) while still behind P (so not in Y): X ∪ Y is
// not convex. Conversely if Y ⊆ X' and X ⊆ Y', then X' ∩ Y' ∩ P⁻ = X and X' ∩ Y' ∩ P⁺ = Y, so
// X ∪ Y = X' ∩ Y', which is convex. The vertex test is made with a small slack, so the volume of
// X' ∩ Y' is compared with the two volumes as a second guard.
#include "visibility/convex_merge.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <utility>

namespace gv {
namespace {

/// How far (relative to the scene's size) a vertex may lie outside the other part's halfspace:
/// the BSP's cells meet in planes shared exactly, so their vertices agree to rounding (~1e-12 of
/// the scene); 1e-8 leaves room for that and no more.
constexpr double kRelativeVertexSlack = 1e-8;
/// The merged shape may exceed the parts' volumes by this fraction (rounding of the volumes).
constexpr double kRelativeVolumeSlack = 1e-7;

/// A union of cells under construction: its convex shape (halfspaces, vertices, volume) or its
/// blind leaves, and its patches.
struct Part {
  std::vector<Plane> halfspaces;
  std::vector<Vec3> vertices;
  double volume = 0;
  std::vector<uint32_t> patches;  // sorted
  std::vector<uint32_t> facing;   // sorted: Cell::facingPatches
  bool hasInterior = false;
  bool blind = false;                     // no patch faces into it
  std::optional<ConvexPolyhedron> shape;  // set once merged as a convex union
  std::vector<uint32_t> leaves;           // set when merged as blind cells (not convex)
};

std::vector<Vec3> verticesOf(const ConvexPolyhedron& shape) {
  std::vector<Vec3> v;
  for (const PolyhedronFace& f : shape.faces)
    v.insert(v.end(), f.polygon.vertices.begin(), f.polygon.vertices.end());
  std::sort(v.begin(), v.end(), [](const Vec3& a, const Vec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  });
  v.erase(std::unique(
              v.begin(), v.end(),
              [](const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }),
          v.end());
  return v;
}

/// h's plane is p's, facing either way.
bool onPlane(const Plane& h, const Plane& p, const Tolerance& tol) {
  const double d = dot(h.normal, p.normal);
  if (std::abs(std::abs(d) - 1) > tol.normalCos()) return false;
  return std::abs(h.offset - (d > 0 ? p.offset : -p.offset)) <= tol.planeOffset();
}

/// Every vertex of `a` within every halfspace of `b` not on `shared`, up to `slack`.
bool insideExceptShared(const Part& a, const Part& b, const Plane& shared, double slack,
                        const Tolerance& tol) {
  for (const Plane& h : b.halfspaces) {
    if (onPlane(h, shared, tol)) continue;
    for (const Vec3& v : a.vertices)
      if (h.distance(v) > slack) return false;
  }
  return true;
}

/// Some patch of the two parts lies in the shared plane: then their common face is not all open
/// (in a convex union the two faces on that plane coincide, so such a patch lies on it). "In the
/// plane" is the BSP's own rule for the patches it cuts portals around: every vertex within the
/// model tolerance of it, whatever the patch's normal (plane_set.h merges normals up to 1e-3 rad:
/// a normal test here let a tilted wall through, and the merged cell held it inside).
bool patchOnPlane(const Scene& scene, const Part& a, const Part& b, const Plane& shared,
                  const Tolerance& tol) {
  for (const Part* part : {&a, &b})
    for (uint32_t p : part->patches) {
      const ConvexPolygon& poly = scene.patches[p].polygon;
      if (std::all_of(poly.vertices.begin(), poly.vertices.end(), [&](const Vec3& v) {
            return std::abs(shared.distance(v)) <= tol.planeOffset();
          }))
        return true;
    }
  return false;
}

/// The BSP node holding the portal has a patch of either part among its coplanar fragments (the
/// opaque parts of its plane, which the portals were cut around).
bool nodeHoldsPatchOf(const BspTree& tree, int32_t node, const Part& a, const Part& b) {
  if (node < 0 || static_cast<size_t>(node) >= tree.nodes.size()) return false;
  for (const PatchFragment& f : tree.nodes[static_cast<size_t>(node)].coplanar)
    for (const Part* part : {&a, &b})
      if (std::binary_search(part->patches.begin(), part->patches.end(), f.patch)) return true;
  return false;
}

uint32_t findRoot(std::vector<uint32_t>& parent, uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

}  // namespace

Subdivision mergeConvexCells(const Scene& scene, Subdivision sub, ConvexMergeStats* stats) {
  const Tolerance tol = sub.tree.tol;
  const double slack = kRelativeVertexSlack * tol.scale;
  const size_t n = sub.cells.size();
  std::vector<Part> parts(n);
  for (size_t c = 0; c < n; ++c) {
    const Cell& cell = sub.cells[c];
    parts[c].halfspaces = cell.shape.halfspaces;
    parts[c].vertices = verticesOf(cell.shape);
    parts[c].volume = cell.shape.volume();
    parts[c].patches = cell.patches;
    parts[c].facing = cell.facingPatches;
    parts[c].hasInterior = !cell.interiorPatches.empty();
    parts[c].blind = !somePatchFacesInto(scene, cell);
  }

  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  // Largest openings first: they are the splits through the middle of rooms.
  std::vector<uint32_t> order(sub.portals.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<double> area(sub.portals.size());
  for (size_t i = 0; i < sub.portals.size(); ++i) area[i] = sub.portals[i].polygon.area();
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return area[a] > area[b]; });

  // Blind cells (the level's outside, seen only through the backs of its walls and through
  // cracks) join their blind neighbours whatever their shapes: see convex_merge.h.
  for (const Portal& portal : sub.portals) {
    const uint32_t x = findRoot(parent, portal.back), y = findRoot(parent, portal.front);
    if (x == y || !parts[x].blind || !parts[y].blind) continue;
    Part& a = parts[x];
    Part& b = parts[y];
    if (a.leaves.empty()) a.leaves.push_back(x);
    if (b.leaves.empty()) b.leaves.push_back(y);
    a.leaves.insert(a.leaves.end(), b.leaves.begin(), b.leaves.end());
    std::vector<uint32_t> patches;
    std::set_union(a.patches.begin(), a.patches.end(), b.patches.begin(), b.patches.end(),
                   std::back_inserter(patches));
    a.patches = std::move(patches);
    b = Part{};
    parent[y] = x;
  }

  for (bool merged = true; merged;) {
    merged = false;
    for (uint32_t pid : order) {
      const Portal& portal = sub.portals[pid];
      const uint32_t x = findRoot(parent, portal.back), y = findRoot(parent, portal.front);
      if (x == y) continue;
      Part& a = parts[x];
      Part& b = parts[y];
      if (a.hasInterior || b.hasInterior || !a.leaves.empty() || !b.leaves.empty()) continue;
      // The plane the BSP split on, not the portal polygon's own (rounded) plane.
      const bool hasNode =
          portal.node >= 0 && static_cast<size_t>(portal.node) < sub.tree.nodes.size();
      const Plane& shared = hasNode ? sub.tree.nodes[static_cast<size_t>(portal.node)].splitter
                                    : portal.polygon.plane;
      if (!insideExceptShared(a, b, shared, slack, tol) ||
          !insideExceptShared(b, a, shared, slack, tol) || patchOnPlane(scene, a, b, shared, tol) ||
          nodeHoldsPatchOf(sub.tree, portal.node, a, b))
        continue;
      std::vector<Plane> planes;
      for (const Part* part : {&a, &b})
        for (const Plane& h : part->halfspaces)
          if (!onPlane(h, shared, tol)) planes.push_back(h);
      std::optional<ConvexPolyhedron> hull = ConvexPolyhedron::fromHalfspaces(planes, tol);
      if (!hull) continue;
      const double volume = hull->volume();
      if (volume > (a.volume + b.volume) * (1 + kRelativeVolumeSlack)) continue;
      Part m;
      m.halfspaces = hull->halfspaces;
      m.vertices = verticesOf(*hull);
      m.volume = volume;
      std::set_union(a.patches.begin(), a.patches.end(), b.patches.begin(), b.patches.end(),
                     std::back_inserter(m.patches));
      std::set_union(a.facing.begin(), a.facing.end(), b.facing.begin(), b.facing.end(),
                     std::back_inserter(m.facing));
      m.shape = std::move(hull);
      parts[x] = std::move(m);
      parts[y] = Part{};
      parent[y] = x;
      merged = true;
    }
  }

  // Number the cells in the order of their first leaf; renumber the portals kept.
  constexpr uint32_t kNone = UINT32_MAX;
  Subdivision out;
  out.stats = sub.stats;
  std::vector<uint32_t> cellOf(n, kNone), rootCell(n, kNone);
  std::vector<uint32_t> partOf(n, kNone);  // a blind leaf's index among its cell's parts
  for (uint32_t c = 0; c < n; ++c) {
    const uint32_t r = findRoot(parent, c);
    if (rootCell[r] == kNone) {
      rootCell[r] = static_cast<uint32_t>(out.cells.size());
      Cell cell;
      if (parts[r].shape) {
        cell.shape = std::move(*parts[r].shape);
        cell.patches = std::move(parts[r].patches);
        cell.facingPatches = std::move(parts[r].facing);
      } else if (!parts[r].leaves.empty()) {
        std::sort(parts[r].leaves.begin(), parts[r].leaves.end());
        for (uint32_t leaf : parts[r].leaves) {
          partOf[leaf] = static_cast<uint32_t>(cell.parts.size());
          cell.parts.push_back({sub.cells[leaf].shape, sub.cells[leaf].patches, {}, {}});
        }
        cell.patches = std::move(parts[r].patches);
      } else {
        cell.shape = sub.cells[c].shape;
        cell.patches = sub.cells[c].patches;
        cell.facingPatches = sub.cells[c].facingPatches;
        cell.interiorPatches = sub.cells[c].interiorPatches;
      }
      out.cells.push_back(std::move(cell));
    }
    cellOf[c] = rootCell[r];
  }
  for (const Portal& p : sub.portals) {
    Portal q = p;
    q.back = cellOf[p.back];
    q.front = cellOf[p.front];
    if (q.back == q.front) {
      // Between two leaves of one cell: merged blind leaves keep it as an inner opening (two
      // leaves merged as a convex union have none: their common face is gone).
      Cell& cell = out.cells[q.back];
      if (cell.parts.empty()) continue;
      const auto inner = static_cast<uint32_t>(cell.innerPortals.size());
      cell.innerPortals.push_back({p.polygon, partOf[p.back], partOf[p.front]});
      cell.parts[partOf[p.back]].innerPortals.push_back(inner);
      cell.parts[partOf[p.front]].innerPortals.push_back(inner);
      continue;
    }
    const auto id = static_cast<uint32_t>(out.portals.size());
    out.cells[q.back].portals.push_back(id);
    out.cells[q.front].portals.push_back(id);
    if (partOf[p.back] != kNone) out.cells[q.back].parts[partOf[p.back]].portals.push_back(id);
    if (partOf[p.front] != kNone) out.cells[q.front].parts[partOf[p.front]].portals.push_back(id);
    out.portals.push_back(std::move(q));
  }
  if (sub.leafCell.empty()) {
    out.leafCell = cellOf;
  } else {
    out.leafCell.resize(sub.leafCell.size());
    for (size_t l = 0; l < sub.leafCell.size(); ++l) out.leafCell[l] = cellOf[sub.leafCell[l]];
  }
  out.stats.cells = out.cells.size();
  out.stats.portals = out.portals.size();
  out.tree = std::move(sub.tree);  // last: the merge above still reads sub.tree's nodes
  if (stats) {
    stats->cellsBefore = n;
    stats->cellsAfter = out.cells.size();
    stats->portalsBefore = sub.portals.size();
    stats->portalsAfter = out.portals.size();
  }
  return out;
}

}  // namespace gv
