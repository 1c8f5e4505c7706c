// render.png, mesh.png, links_visible.png, links_partial.png.
#include "render/radiosity_pictures.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "radiosity/element_mesh.h"
#include "render/default_camera.h"
#include "render/element_bvh.h"
#include "render/png_image.h"
#include "render/segment_drawing.h"
#include "render/tone_map.h"
#include "util/timing.h"

namespace gv {
namespace {

/// Largest accepted image side (pixels): beyond it a typo would allocate gigabytes.
constexpr int kMaxImageSide = 16384;

RgbImage dimmed(RgbImage image) {
  for (uint8_t& c : image.pixels) c = static_cast<uint8_t>(std::lround(kUnderlayDim * c));
  return image;
}

/// Only edges of faces whose front the camera sees (the others are culled in the picture).
bool facesCamera(const Element& element, const Camera& camera) {
  return element.polygon.plane.distance(camera.eye) > 0;
}

}  // namespace

PictureOptions parsePictureOptions(const std::string& camera, const std::string& imageSize,
                                   bool flat) {
  PictureOptions options;
  int w = 0, h = 0;
  char extra = 0;
  if (std::sscanf(imageSize.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 1 || h < 1 ||
      w > kMaxImageSide || h > kMaxImageSide)
    throw std::invalid_argument("image size: expected WxH with 1 <= W, H <= " +
                                std::to_string(kMaxImageSide) + ", got '" + imageSize + "'");
  options.width = w;
  options.height = h;
  if (!camera.empty()) {
    Camera c;
    c.width = w;
    c.height = h;
    options.camera = parseCamera(camera, c);
  }
  options.shading = flat ? Shading::Flat : Shading::Smooth;
  return options;
}

std::string pictureOptionsError(const std::string& camera, const std::string& imageSize) {
  try {
    parsePictureOptions(camera, imageSize, false);
    return {};
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

PictureStats writeRadiosityPictures(const Scene& scene, const RadiosityResult& result,
                                    const std::filesystem::path& dir,
                                    const PictureOptions& options) {
  const auto start = Clock::now();
  PictureStats stats;
  stats.camera = options.camera
                     ? *options.camera
                     : defaultCamera(scene, result.patchRadiosity, options.width, options.height);
  const Camera& camera = stats.camera;
  camera.validate();

  const ElementMesh mesh = buildElementMesh(result);
  const ElementBvh bvh(mesh, result.elements);
  const RenderBuffers buffers = renderRadiosity(result, mesh, bvh, camera, options.shading);
  const auto notEmitter = [&](uint32_t face) {
    const uint32_t patch = result.elements[mesh.faceElement[face]].patch;
    return !scene.materials[scene.patches[patch].material].isEmitter();
  };
  stats.white = options.white > 0 ? options.white : automaticWhite(buffers, notEmitter);
  for (uint32_t f : buffers.face) stats.coveredPixels += f != kNoFace;
  const RgbImage picture = toneMap(buffers, stats.white);

  // Every link of a class when there are at most kMaxDrawnLinks, else every k-th (in the
  // solver's order, which follows the refinement, so the sample spreads over the whole scene).
  std::vector<uint32_t> visibleLinks, partialLinks;
  for (uint32_t l = 0; l < result.links.size(); ++l) {
    if (result.links[l].status == VisibilityStatus::Visible) visibleLinks.push_back(l);
    if (result.links[l].status == VisibilityStatus::Partial) partialLinks.push_back(l);
  }
  stats.visibleLinks = visibleLinks.size();
  stats.partialLinks = partialLinks.size();
  const RgbImage under = dimmed(picture);
  const auto drawLinks = [&](const std::vector<uint32_t>& links,
                             const std::array<uint8_t, 3>& colour, size_t& drawn,
                             const char* name) {
    RgbImage image = under;
    const size_t stride = std::max<size_t>(1, (links.size() + kMaxDrawnLinks - 1) / kMaxDrawnLinks);
    const SegmentStyle style{colour, kLinkOpacity, true};
    for (size_t k = 0; k < links.size(); k += stride) {
      const Link& link = result.links[links[k]];
      drawSegment(image, camera, buffers.depth, result.elements[link.a].polygon.centroid(),
                  result.elements[link.b].polygon.centroid(), style);
      ++drawn;
    }
    writePng(image, (dir / name).string());
  };
  const auto drawMesh = [&] {
    RgbImage image = picture;
    const SegmentStyle edgeStyle{{0, 0, 0}, kEdgeOpacity, true};
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      if (!facesCamera(result.elements[mesh.faceElement[f]], camera)) continue;
      const std::vector<uint32_t>& face = mesh.faces[f];
      for (size_t k = 0; k < face.size(); ++k)
        drawSegment(image, camera, buffers.depth, mesh.positions[face[k]],
                    mesh.positions[face[(k + 1) % face.size()]], edgeStyle);
    }
    writePng(image, (dir / "mesh.png").string());
  };
  // The four pictures are independent (each its own image and file).
  tbb::parallel_invoke(
      [&] { writePng(picture, (dir / "render.png").string()); }, drawMesh,
      [&] {
        drawLinks(visibleLinks, kVisibleLinkColour, stats.visibleLinksDrawn, "links_visible.png");
      },
      [&] {
        drawLinks(partialLinks, kPartialLinkColour, stats.partialLinksDrawn, "links_partial.png");
      });
  stats.seconds = secondsSince(start);
  return stats;
}

}  // namespace gv
