// The Cornell box with its published measured geometry: the classic radiosity test scene.
#pragma once

#include "scene/scene.h"

namespace gv {

/// Variations on the published box.
struct CornellBoxOptions {
  /// The published box is open at the front (z = 0, where the camera looks in). true adds a white
  /// front wall facing inward so that the box is closed (no light escapes; every ray from inside
  /// hits a patch). Default false: the published, open box.
  bool closedFront = false;
};

/// The Cornell box from the Cornell University Program of Computer Graphics "Cornell Box Data"
/// page (https://www.graphics.cornell.edu/online/box/data.html), in its published units:
/// millimetres, y up, the camera at z < 0 looking along +z; the red wall is at x ~ 556 (seen on the
/// left), the green one at x = 0.
///
/// Patches: floor, ceiling, back wall, green wall, red wall (the published red wall is not planar:
/// its corners leave a plane by 3 mm, so it is two triangles), the light, and the short and tall
/// blocks as closed solids facing outward (the published five faces plus a bottom face on the
/// floor): 19 patches, 20 with `closedFront`. The walls face inward.
///
/// The data gives the light (343..213 x 227..332) and the full ceiling quad the same height
/// y = 548.8 (no hole). Coplanar overlapping patches are ambiguous, so the ceiling is kept whole as
/// published and the light, facing down, is lowered by 0.5 mm to y = 548.3.
///
/// Materials (RGB reductions of the measured spectra, as in Morgan McGuire's Computer Graphics
/// Archive "CornellBox-Original" MTL, the values most renderers use): white Kd (0.725, 0.71, 0.68),
/// red (0.63, 0.065, 0.05), green (0.14, 0.45, 0.091); light Ke (17, 12, 4) with Kd 0.78 (the same
/// archive's light), taken as the emitted radiosity per this project's MTL convention.
Scene generateCornellBox(const CornellBoxOptions& options = {});

}  // namespace gv
