// The pictures `globalvis radiosity` writes: the solution (render.png), the refined mesh
// (mesh.png) and the paper's Fig. 14 link pictures (links_visible.png, links_partial.png).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "radiosity/hierarchical_radiosity.h"
#include "render/camera.h"
#include "render/render.h"
#include "scene/scene.h"

namespace gv {

/// What to draw and from where.
struct PictureOptions {
  std::optional<Camera> camera;   ///< nullopt: defaultCamera(scene, width, height)
  int width = 800, height = 600;  ///< image size when `camera` is nullopt
  Shading shading = Shading::Smooth;
  double white = 0;  ///< exposure (tone_map.h); <= 0: automatic (99th percentile)
};

/// Picture options from the command line's text: `camera` as parseCamera takes it (empty: the
/// default camera), `imageSize` as `WxH` (each 1..16384), flat or smooth shading. Throws
/// std::invalid_argument with a message naming the bad part.
PictureOptions parsePictureOptions(const std::string& camera, const std::string& imageSize,
                                   bool flat);

/// The message parsePictureOptions(camera, imageSize, false) would throw, or "" when none (a
/// CLI11 validator).
std::string pictureOptionsError(const std::string& camera, const std::string& imageSize);

/// What was drawn.
struct PictureStats {
  Camera camera;                                        ///< the camera used
  double white = 0;                                     ///< the exposure used
  size_t coveredPixels = 0;                             ///< pixels that see a surface
  size_t visibleLinks = 0, partialLinks = 0;            ///< in the solution
  size_t visibleLinksDrawn = 0, partialLinksDrawn = 0;  ///< in the pictures
  double seconds = 0;
};

/// Colour of VISIBLE links (the paper's Fig. 14: white) and of PARTIAL links (green).
inline constexpr std::array<uint8_t, 3> kVisibleLinkColour{255, 255, 255};
inline constexpr std::array<uint8_t, 3> kPartialLinkColour{40, 255, 40};
/// Opacity of one link line (overlapping lines add up towards solid colour).
inline constexpr double kLinkOpacity = 0.6;
/// Opacity of the black element edges of mesh.png (light enough that dense meshes stay readable).
inline constexpr double kEdgeOpacity = 0.35;
/// At most this many links of each class are drawn.
inline constexpr size_t kMaxDrawnLinks = 4000;
/// The scene under the links and edges is dimmed to this fraction (in 8-bit sRGB values).
inline constexpr double kUnderlayDim = 0.35;

/// Writes into `dir`:
///  - render.png: the solution, tone-mapped (tone_map.h);
///  - mesh.png: the same picture with the leaf elements' edges drawn in black (Fig. 14 left),
///    edges of elements facing away from the camera left out;
///  - links_visible.png / links_partial.png: every VISIBLE (white) or PARTIAL (green) link of
///    the final solution as a segment between the centroids of its two elements, over the
///    dimmed picture. A refined solution has 10^4..10^6 links, which would paint every pixel, so
///    at most kMaxDrawnLinks of each class are drawn (every k-th, evenly over the solver's link
///    order), as in the paper's figure, whose densest panel shows a few thousand: where links
///    are dense the scene is unoccluded (white), occlusion shows in green. Segments and edges are
///    depth-tested against the picture (a link is hidden where a surface the camera sees is in
///    front of it) and clipped by the camera's cutaway.
/// Throws InputError when a file cannot be written, std::invalid_argument for a bad camera.
PictureStats writeRadiosityPictures(const Scene& scene, const RadiosityResult& result,
                                    const std::filesystem::path& dir,
                                    const PictureOptions& options = {});

}  // namespace gv
