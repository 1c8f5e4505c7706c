// Element subdivision rules and the element forest. HSA91 §4 (quadtree refinement).
#include "radiosity/element_tree.h"

#include <algorithm>
#include <cmath>

#include "util/check.h"

namespace gv {
namespace {

ConvexPolygon piece(std::vector<Vec3> vertices, const Plane& plane) {
  // Built directly, not via fromVertices: midpoints of a convex polygon's edges and its interior
  // points give convex pieces by construction, and refitting a plane would let children drift
  // from their parent's plane.
  return ConvexPolygon{std::move(vertices), plane};
}

}  // namespace

std::vector<ConvexPolygon> splitElementPolygon(const ConvexPolygon& polygon) {
  const std::vector<Vec3>& v = polygon.vertices;
  const Plane& plane = polygon.plane;
  CHECK_MSG(v.size() >= 3, "an element with {} vertices", v.size());
  std::vector<ConvexPolygon> out;
  if (v.size() == 3) {
    const Vec3 m01 = (v[0] + v[1]) * 0.5, m12 = (v[1] + v[2]) * 0.5, m20 = (v[2] + v[0]) * 0.5;
    out.push_back(piece({v[0], m01, m20}, plane));
    out.push_back(piece({m01, v[1], m12}, plane));
    out.push_back(piece({m20, m12, v[2]}, plane));
    out.push_back(piece({m01, m12, m20}, plane));
  } else if (v.size() == 4) {
    const Vec3 m01 = (v[0] + v[1]) * 0.5, m12 = (v[1] + v[2]) * 0.5;
    const Vec3 m23 = (v[2] + v[3]) * 0.5, m30 = (v[3] + v[0]) * 0.5;
    // Midline m30-m12 runs across edges 30 and 12 (the "u" direction), m01-m23 the other way.
    const double lengthU = distance(m30, m12), lengthV = distance(m01, m23);
    if (lengthU > kMaxAspect * lengthV) {
      // Long along u: cut by the midline m01-m23, which crosses the long direction.
      out.push_back(piece({v[0], m01, m23, v[3]}, plane));
      out.push_back(piece({m01, v[1], v[2], m23}, plane));
    } else if (lengthV > kMaxAspect * lengthU) {
      out.push_back(piece({v[0], v[1], m12, m30}, plane));
      out.push_back(piece({m30, m12, v[2], v[3]}, plane));
    } else {
      const Vec3 c = (v[0] + v[1] + v[2] + v[3]) * 0.25;
      out.push_back(piece({v[0], m01, c, m30}, plane));
      out.push_back(piece({m01, v[1], m12, c}, plane));
      out.push_back(piece({c, m12, v[2], m23}, plane));
      out.push_back(piece({m30, c, m23, v[3]}, plane));
    }
  } else {
    const Vec3 c = polygon.centroid();
    for (size_t i = 0; i < v.size(); ++i)
      out.push_back(piece({c, v[i], v[(i + 1) % v.size()]}, plane));
  }
  return out;
}

ElementTree::ElementTree(const Scene& scene) : patchCount_(scene.patches.size()) {
  elements_.reserve(scene.patches.size());
  for (size_t id = 0; id < scene.patches.size(); ++id) {
    Element e;
    e.polygon = scene.patches[id].polygon;
    e.area = e.polygon.area();
    e.patch = static_cast<uint32_t>(id);
    elements_.push_back(std::move(e));
  }
}

bool ElementTree::subdivide(uint32_t id) {
  if (!elements_[id].isLeaf()) return true;
  std::vector<ConvexPolygon> pieces = splitElementPolygon(elements_[id].polygon);
  if (pieces.empty()) return false;
  const auto first = static_cast<uint32_t>(elements_.size());
  const uint32_t patch = elements_[id].patch, depth = elements_[id].depth + 1;
  for (ConvexPolygon& p : pieces) {
    Element child;
    child.area = p.area();
    child.polygon = std::move(p);
    child.patch = patch;
    child.parent = id;
    child.depth = depth;
    elements_.push_back(std::move(child));
  }
  elements_[id].firstChild = first;
  elements_[id].childCount = static_cast<uint32_t>(pieces.size());
  return true;
}

namespace {

/// The smallest signed distance from `p` (in the polygon's plane) to the lines of its edges,
/// positive inside: the polygon's normal orients the edges counter-clockwise.
double insideDepth(const ConvexPolygon& polygon, const Vec3& p) {
  const std::vector<Vec3>& v = polygon.vertices;
  double depth = INFINITY;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 edge = v[(i + 1) % v.size()] - v[i];
    const Vec3 inward = cross(polygon.plane.normal, edge);
    const double len = length(inward);
    if (len > 0) depth = std::min(depth, dot(p - v[i], inward) / len);
  }
  return depth;
}

}  // namespace

uint32_t ElementTree::deepestContaining(uint32_t root, const Vec3& p, double minArea) const {
  uint32_t e = root;
  while (!elements_[e].isLeaf()) {
    const Element& el = elements_[e];
    if (elements_[el.firstChild].area < minArea) break;
    uint32_t best = el.firstChild;
    double bestDepth = -INFINITY;
    for (uint32_t c = el.firstChild; c < el.firstChild + el.childCount; ++c) {
      const double d = insideDepth(elements_[c].polygon, p);
      if (d > bestDepth) {
        bestDepth = d;
        best = c;
      }
      if (d >= 0) break;  // children do not overlap: the first that contains p is the one
    }
    e = best;
  }
  return e;
}

size_t ElementTree::leafCount() const {
  return static_cast<size_t>(std::count_if(elements_.begin(), elements_.end(),
                                           [](const Element& e) { return e.isLeaf(); }));
}

}  // namespace gv
