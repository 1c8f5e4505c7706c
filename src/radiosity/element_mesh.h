// The leaf elements of a radiosity solution as an indexed mesh with smooth per-vertex radiosity
// (HSA91 §5 displays the same way): what elements.ply stores and what the renderer shades with.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/vec3.h"
#include "radiosity/hierarchical_radiosity.h"

namespace gv {

/// Leaf elements sharing vertices within their patch (never across patches, so shading stays
/// sharp at creases and between differently lit patches).
struct ElementMesh {
  std::vector<Vec3> positions;       ///< one per shared vertex
  std::vector<Rgb> vertexRadiosity;  ///< area-weighted mean radiosity of the leaves touching it
  /// Leaf faces: vertex indices, counter-clockwise from the front (the element's orientation).
  std::vector<std::vector<uint32_t>> faces;
  std::vector<uint32_t> faceElement;  ///< element id of each face
};

/// Builds the mesh of `result`'s leaf elements. A vertex is shared by the leaves of one patch
/// that have a corner at exactly that position (midpoints are computed identically from the same
/// end points, so equal positions have equal bits); its radiosity is the area-weighted mean of
/// theirs. A T-junction corner (a leaf's corner on a larger neighbour's edge) only averages the
/// leaves that have it as a corner.
ElementMesh buildElementMesh(const RadiosityResult& result);

}  // namespace gv
