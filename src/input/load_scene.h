// Scene input: the one call that turns any scene file into a Scene, choosing the importer by the
// file's extension. It sits above the importers (scene/ for OBJ and Assimp formats, quake/ for
// .map level sources) so that none of them has to know about the others.
#pragma once

#include <string>

#include "scene/scene.h"

namespace gv {

/// Loads a scene file, choosing the reader by extension: .obj (importObj), .map (Quake level
/// source, quake/map_to_scene.h: importMap), anything else Assimp reads (importWithAssimp). Faces
/// become convex patches by the rules of face_to_patches.h; `Scene::report` tells what happened to
/// them. Throws InputError (naming file and line) on unreadable or malformed input, non-finite
/// coordinates, bad indices, faces with fewer than 3 vertices, or a scene with no usable face.
Scene loadScene(const std::string& path);

/// loadScene, then, when `contactSplit`, splitPatchesAtContacts (scene/contact_split.h): what
/// `radiosity` and `photons` read by default and `vis --contact-split`.
Scene loadScene(const std::string& path, bool contactSplit);

}  // namespace gv
