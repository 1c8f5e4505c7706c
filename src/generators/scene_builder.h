// Helpers for procedural scenes: add convex polygons, quads and axis-aligned boxes as patches.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/tolerance.h"
#include "geometry/vec3.h"
#include "scene/scene.h"

namespace gv {

/// Faces of an axis-aligned box, as bits, so a caller can leave some out.
enum BoxFace : uint32_t {
  kBoxMinX = 1u << 0,
  kBoxMaxX = 1u << 1,
  kBoxMinY = 1u << 2,
  kBoxMaxY = 1u << 3,
  kBoxMinZ = 1u << 4,
  kBoxMaxZ = 1u << 5,
  kBoxAllFaces = 0x3fu,
};

/// One material index per box face, in BoxFace bit order: -x, +x, -y, +y, -z, +z.
struct BoxMaterials {
  std::array<uint32_t, 6> face{};
  /// The same material on all six faces.
  static BoxMaterials uniform(uint32_t material) {
    BoxMaterials m;
    m.face.fill(material);
    return m;
  }
};

/// Appends patches to a scene. Generators know their extent before they start, so the builder
/// takes the tolerance up front (Tolerance::forBounds of the final scene's box) instead of
/// recomputing scene bounds per patch; that keeps building O(patches).
///
/// Choice about hidden faces: addBox adds all six faces by default, i.e. every solid is closed and
/// oriented outward, even where it touches another solid (a wall's bottom face on a floor slab).
/// Such a face faces into the neighbouring solid and sees nothing, which costs a patch but keeps
/// each solid closed, as real models built from solids are; visibility code must cope with
/// back-to-back coplanar faces anyway. The `faces` mask is for the one case where dropping faces
/// is exact: two faces that coincide exactly with opposite orientations, both invisible. Dropping
/// both keeps the union's surface closed (their divergence-theorem terms cancel).
class SceneBuilder {
 public:
  SceneBuilder(Scene& scene, const Tolerance& tol) : scene_(scene), tol_(tol) {}

  /// Adds a convex planar polygon, counter-clockwise seen from its front. Returns false (and adds
  /// nothing) when it is degenerate at the builder's tolerance.
  bool addPolygon(std::vector<Vec3> vertices, uint32_t material);
  /// Adds quad a-b-c-d (counter-clockwise from the front, convex). A quad whose fourth vertex
  /// strays from the plane of the first three by more than kRelativeModelEpsilon of its diameter
  /// is added as two triangles (a,b,c) and (a,c,d) so that every patch is exactly planar. Returns
  /// the number of patches added (0, 1 or 2).
  int addQuad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, uint32_t material);
  /// Adds the faces of the axis-aligned box [lo, hi] selected by `faces` (BoxFace bits), each
  /// facing outward (front = air side, counter-clockwise seen from outside). Returns patches added.
  int addBox(const Vec3& lo, const Vec3& hi, const BoxMaterials& materials,
             uint32_t faces = kBoxAllFaces);
  /// addBox with one material on every face.
  int addBox(const Vec3& lo, const Vec3& hi, uint32_t material, uint32_t faces = kBoxAllFaces) {
    return addBox(lo, hi, BoxMaterials::uniform(material), faces);
  }
  /// Adds the axis-aligned rectangle lo..hi lying in the plane `axis` = lo[axis] (= hi[axis]),
  /// facing +axis when `positive`, else -axis. Returns false if degenerate.
  bool addAxisRect(int axis, bool positive, const Vec3& lo, const Vec3& hi, uint32_t material);

  Scene& scene() { return scene_; }
  const Tolerance& tolerance() const { return tol_; }

 private:
  Scene& scene_;
  Tolerance tol_;
};

}  // namespace gv
