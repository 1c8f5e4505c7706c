// The office (or any scene) as `globalvis radiosity` reads it, and its cells: for the tests of the
// cell culling (visibility/patch_cell_reach.h) and of the radiosity that uses it.
#pragma once

#include "bsp/hidden_faces.h"
#include "bsp/subdivision.h"
#include "generators/office.h"
#include "scene/contact_split.h"
#include "visibility/patch_cell_reach.h"

namespace gv::test {

/// Two storeys of one row of three rooms, with doors and windows: light goes from room to room
/// and along the corridors, never between storeys.
inline OfficeOptions twoStoreysOfThreeRooms() {
  OfficeOptions o;
  o.floors = 2;
  o.rows = 1;
  o.columns = 3;
  return o;
}

/// `scene` as loadPipelineScene hands it to `radiosity`: cut along its contacts (a floor along
/// the walls standing on it), then the faces no air reaches dropped (wall ends in the slabs).
inline Scene asRadiosityReadsIt(Scene scene) {
  splitPatchesAtContacts(scene);
  HiddenFaceOptions hidden;
  hidden.cutPartly = true;
  return removeHiddenFaces(scene, hidden);
}

/// The office as `radiosity` reads it.
inline Scene radiosityOffice(const OfficeOptions& o) {
  return asRadiosityReadsIt(generateOffice(o));
}

/// Whether `c` lies in `box` grown by `margin` on every side.
inline bool insideGrown(const Aabb& box, const Vec3& c, double margin) {
  return c.x >= box.lo.x - margin && c.x <= box.hi.x + margin && c.y >= box.lo.y - margin &&
         c.y <= box.hi.y + margin && c.z >= box.lo.z - margin && c.z <= box.hi.z + margin;
}

/// PatchCellReach over `vis`'s cells of the scene, 2 threads.
inline PatchCellReach cellReachOf(const Scene& scene) {
  const Subdivision sub = buildVisibilitySubdivision(scene, BspOptions{});
  PropagationOptions options;
  options.threads = 2;
  return PatchCellReach(scene, sub, options);
}

}  // namespace gv::test
