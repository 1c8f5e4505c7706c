// Portals: the boundary between two leaf cells minus the patches coaffine with it, as convex
// pieces; and the list of coaffine patches of every boundary face. Paper §3.
#include "bsp/portals.h"

#include <algorithm>
#include <utility>

#include "bsp/box_grid.h"
#include "bsp/coplanar_clip.h"
#include "scene/face_to_patches.h"

namespace gv {
namespace {

/// A leaf face lying on some node's plane.
struct FaceRef {
  uint32_t cell = 0;
  uint32_t face = 0;
};

/// The bounds of a polygon in the plane's 2D coordinates (the two axes other than the normal's
/// dominant one), widened by `slack` so that touching counts as overlapping.
Box2 box2(const ConvexPolygon& p, int dropAxis, double slack) {
  const int a = (dropAxis + 1) % 3, b = (dropAxis + 2) % 3;
  Box2 box{p.vertices[0][a], p.vertices[0][b], p.vertices[0][a], p.vertices[0][b]};
  for (const Vec3& v : p.vertices) {
    box.u0 = std::min(box.u0, v[a]), box.u1 = std::max(box.u1, v[a]);
    box.v0 = std::min(box.v0, v[b]), box.v1 = std::max(box.v1, v[b]);
  }
  box.u0 -= slack, box.v0 -= slack, box.u1 += slack, box.v1 += slack;
  return box;
}

void sortUnique(std::vector<uint32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

void buildPortals(Subdivision& sub) {
  const BspTree& tree = sub.tree;
  const Tolerance& tol = tree.tol;
  const double slack = tol.length();

  // Which leaf faces lie on each node's plane, and on which side.
  std::vector<std::vector<FaceRef>> frontFaces(tree.nodes.size()), backFaces(tree.nodes.size());
  for (uint32_t c = 0; c < sub.cells.size(); ++c) {
    const ConvexPolyhedron& shape = sub.cells[c].shape;
    for (uint32_t i = 0; i < shape.faces.size(); ++i) {
      const int node = shape.faces[i].planeId;
      sub.cells[c].faces[i].node = node;
      if (node < 0) continue;
      const Plane& splitter = tree.nodes[static_cast<size_t>(node)].splitter;
      // A face points out of its cell: along the splitter's normal means the cell is behind it.
      const bool cellIsBehind = dot(shape.faces[i].polygon.plane.normal, splitter.normal) > 0;
      (cellIsBehind ? backFaces : frontFaces)[static_cast<size_t>(node)].push_back({c, i});
    }
  }

  auto polygonOf = [&](const FaceRef& f) -> const ConvexPolygon& {
    return sub.cells[f.cell].shape.faces[f.face].polygon;
  };

  for (size_t n = 0; n < tree.nodes.size(); ++n) {
    const BspNode& node = tree.nodes[n];
    const std::vector<FaceRef>& front = frontFaces[n];
    const std::vector<FaceRef>& back = backFaces[n];
    if (front.empty() && back.empty()) continue;
    const int drop = dominantAxis(node.splitter.normal);

    std::vector<Box2> fragmentBoxes;
    fragmentBoxes.reserve(node.coplanar.size());
    for (const PatchFragment& f : node.coplanar)
      fragmentBoxes.push_back(box2(f.polygon, drop, slack));
    BoxGrid2 fragments(std::move(fragmentBoxes));

    // Coaffine patches of every face on this plane: those overlapping it in more than a sliver.
    for (const std::vector<FaceRef>* side : {&front, &back}) {
      for (const FaceRef& f : *side) {
        const ConvexPolygon& poly = polygonOf(f);
        std::vector<uint32_t>& list = sub.cells[f.cell].faces[f.face].coaffinePatches;
        fragments.query(box2(poly, drop, slack), [&](uint32_t k) {
          if (intersectCoplanar(poly, node.coplanar[k].polygon, tol)) {
            list.push_back(node.coplanar[k].patch);
          }
        });
      }
    }

    if (front.empty() || back.empty()) continue;
    std::vector<Box2> frontBoxes;
    frontBoxes.reserve(front.size());
    for (const FaceRef& f : front) frontBoxes.push_back(box2(polygonOf(f), drop, slack));
    BoxGrid2 frontGrid(std::move(frontBoxes));

    std::vector<ConvexPolygon> pieces, next;
    std::vector<uint32_t> overlapping;
    for (const FaceRef& b : back) {
      const ConvexPolygon& backPoly = polygonOf(b);  // faces along the splitter: back → front
      std::vector<uint32_t> partners;
      frontGrid.query(box2(backPoly, drop, slack), [&](uint32_t k) { partners.push_back(k); });
      for (uint32_t k : partners) {
        const FaceRef& f = front[k];
        std::optional<ConvexPolygon> shared = intersectCoplanar(backPoly, polygonOf(f), tol);
        if (!shared) continue;
        // Subtract the opaque patches from the shared boundary.
        pieces.assign(1, std::move(*shared));
        overlapping.clear();
        fragments.query(box2(pieces[0], drop, slack),
                        [&](uint32_t j) { overlapping.push_back(j); });
        for (uint32_t j : overlapping) {
          next.clear();
          for (const ConvexPolygon& piece : pieces) {
            subtractCoplanar(piece, node.coplanar[j].polygon, tol, next);
          }
          std::swap(pieces, next);
          if (pieces.empty()) break;
        }
        for (ConvexPolygon& piece : pieces) {
          // A piece thinner than the model tolerance is a crack between abutting patches (a
          // floor's edge a rounding error short of its wall), not an opening: the scene is only
          // resolved to that tolerance, import drops faces that thin (isSliver), and sightlines
          // through it pass within the tolerance of a patch's edge. Kept, such needles joined
          // the void around a level to its rooms and made every search walk both.
          if (isSliver(piece, tol)) continue;
          const auto id = static_cast<uint32_t>(sub.portals.size());
          sub.portals.push_back({std::move(piece), b.cell, f.cell, static_cast<int32_t>(n)});
          sub.cells[b.cell].faces[b.face].portals.push_back(id);
          sub.cells[f.cell].faces[f.face].portals.push_back(id);
          sub.cells[b.cell].portals.push_back(id);
          sub.cells[f.cell].portals.push_back(id);
        }
      }
    }
  }

  for (Cell& cell : sub.cells) {
    sortUnique(cell.portals);
    for (BoundaryFace& face : cell.faces) {
      sortUnique(face.coaffinePatches);
      sortUnique(face.portals);
    }
  }
}

}  // namespace gv
