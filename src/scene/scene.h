// The scene model: convex one-sided patches with a diffuse material each. What every stage reads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"

namespace gv {

/// Linear RGB triple (reflectance in [0,1] per channel, or radiosity / emission >= 0).
struct Rgb {
  double r = 0, g = 0, b = 0;
  constexpr bool operator==(const Rgb&) const = default;
  constexpr bool isBlack() const { return r == 0 && g == 0 && b == 0; }
  /// The largest channel (the solver's scalar for power and error bounds).
  constexpr double maxChannel() const { return std::max({r, g, b}); }
};

/// A diffuse material. `reflectance` is MTL's Kd, `emission` MTL's Ke (emitted radiosity).
struct Material {
  std::string name;
  Rgb reflectance{0.5, 0.5, 0.5};
  Rgb emission{};
  bool isEmitter() const { return !emission.isBlack(); }
};

/// Sentinel for patches that come from no input face (made by a generator).
inline constexpr uint32_t kNoSourceFace = UINT32_MAX;

/// A patch: a convex planar one-sided polygon (front = counter-clockwise side) with a material.
struct Patch {
  ConvexPolygon polygon;
  uint32_t material = 0;                ///< index into Scene::materials
  uint32_t sourceFace = kNoSourceFace;  ///< 0-based index of the input face it came from
};

/// What import did to the input faces; reported by `globalvis info`.
struct ImportReport {
  size_t facesIn = 0;
  size_t droppedDegenerate = 0;      ///< zero area, repeated or collinear vertices
  size_t splitNonConvex = 0;         ///< planar non-convex faces decomposed into convex pieces
  size_t triangulatedNonPlanar = 0;  ///< faces beyond the planarity tolerance, triangulated
  size_t splitAtContacts = 0;        ///< patches cut along the outlines of patches resting on them
  size_t contactPieces = 0;          ///< the pieces those patches became (scene/contact_split.h)
  /// Faces no air reaches and coincident twins (bsp/hidden_faces.h), when that pass ran.
  size_t hiddenDropped = 0;      ///< patches whose front looks only into closed solids
  size_t coincidentDropped = 0;  ///< same-facing twins wholly covered by earlier patches
  size_t partlyHiddenKept = 0;   ///< patches only partly hidden or covered, kept whole
  size_t frontBeyondAir = 0;     ///< patches with a Scene::beyondAirBounds box
  bool shells = false;           ///< air is inside inward-facing shells (a 2.5D sector level)
  std::vector<std::string> warnings;
};

/// The scene: patches and the materials they index. Patch ids are indices into `patches`.
struct Scene {
  std::vector<Patch> patches;
  std::vector<Material> materials;
  ImportReport report;
  /// Per patch, the box of the parts of its front that look into a region no air reaches (empty
  /// box: none): a closed solid's inside, or on a level of inward-facing shells (2.5D sectors)
  /// the void outside every sector (a lower wall taller than the room it faces). Set by the
  /// hidden-face pass (bsp/hidden_faces.h); an empty vector when not known. `vis` looks for
  /// those parts from the rays that slip into such regions at a wall's end
  /// (visibility/patch_search.cpp).
  std::vector<Aabb> beyondAirBounds;

  Aabb bounds() const;
  /// The scene's tolerance policy instance (see geometry/tolerance.h).
  Tolerance tolerance() const { return Tolerance::forBounds(bounds()); }
  double totalArea() const;
  size_t emitterCount() const;  ///< patches whose material emits
  /// Per patch, its emitted power: area × the largest channel of its emission (0 for most).
  std::vector<double> emittedPower() const;
  /// Adds a material and returns its index.
  uint32_t addMaterial(Material m);
};

}  // namespace gv
