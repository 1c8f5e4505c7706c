// The element hierarchy of hierarchical radiosity (HSA91 §4): each patch is the root of a tree of
// convex sub-polygons ("elements") made on demand when a link is refined (paper §6: "one of the
// patches of the interaction is symmetrically subdivided").
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "geometry/convex_polygon.h"
#include "scene/scene.h"

namespace gv {

/// Sentinel element id.
inline constexpr uint32_t kNoElement = std::numeric_limits<uint32_t>::max();

/// A patch or a piece of one. Children partition their parent exactly (no gaps, no overlaps).
struct Element {
  ConvexPolygon polygon;  ///< in the patch's plane, same orientation
  double area = 0;
  uint32_t patch = 0;                ///< the patch it lies on
  uint32_t parent = kNoElement;      ///< kNoElement for a patch (root)
  uint32_t firstChild = kNoElement;  ///< children are contiguous: firstChild .. firstChild+count-1
  uint32_t childCount = 0;
  uint32_t depth = 0;  ///< 0 for a patch
  bool isLeaf() const { return childCount == 0; }
};

/// A point of an element kept in single precision: a sample's end, so that once its element has
/// been cut further the deepest element there can be found again (ElementTree::deepestContaining
/// picks the nearest child when rounding puts the point just outside all of them).
struct StoredPoint {
  float x = 0, y = 0, z = 0;
  StoredPoint() = default;
  explicit StoredPoint(const Vec3& p)
      : x(static_cast<float>(p.x)), y(static_cast<float>(p.y)), z(static_cast<float>(p.z)) {}
  Vec3 point() const { return {x, y, z}; }
};

/// How an element is cut into children. Quadrilaterals are the common case (HSA91's quadtree):
/// four children through the midpoints of the edges and the vertex mean, except that a quad more
/// than kMaxAspect times longer than wide is cut across its long direction only, into two, so that
/// long thin patches (door jambs, skirting) become squarer rather than staying slivers. Triangles
/// give four by their edge midpoints. Other convex n-gons (n >= 5) give n triangles fanned from
/// their area centroid, which is strictly inside, so every piece has positive area; from then on
/// the triangles follow the triangle rule. All pieces stay convex and in the parent's plane.
std::vector<ConvexPolygon> splitElementPolygon(const ConvexPolygon& polygon);

/// A quad whose midline lengths differ by more than this factor is split in two, not four.
inline constexpr double kMaxAspect = 2.0;

/// The forest of elements over a scene's patches. Element k < patchCount is patch k.
class ElementTree {
 public:
  explicit ElementTree(const Scene& scene);

  const Element& operator[](uint32_t id) const { return elements_[id]; }
  size_t size() const { return elements_.size(); }
  size_t patchCount() const { return patchCount_; }
  std::span<const Element> all() const { return elements_; }

  /// Creates the children of `id` if it has none (see splitElementPolygon); returns whether the
  /// element has children afterwards. Element ids stay valid (children are appended); references
  /// to elements may be invalidated.
  bool subdivide(uint32_t id);

  /// The deepest existing element below `root` (or `root` itself) whose polygon contains `p`, a
  /// point of root's polygon: at each level the child with the largest smallest signed distance
  /// to its edges, so a point on a shared edge or a rounding error away still gets a child.
  /// Stops above children smaller than `minArea` (judged by the first child: siblings are
  /// about equal).
  uint32_t deepestContaining(uint32_t root, const Vec3& p, double minArea = 0) const;

  /// Number of leaves (elements without children).
  size_t leafCount() const;

 private:
  std::vector<Element> elements_;
  size_t patchCount_ = 0;
};

}  // namespace gv
