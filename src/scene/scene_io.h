// Reading and writing scenes: Wavefront OBJ + MTL (Kd = reflectance, Ke = emission).
#pragma once

#include <string>

#include "scene/scene.h"

namespace gv {

/// Loads a scene file, choosing the reader by extension: .obj (importObj), .map (Quake level
/// source, quake/map_to_scene.h: importMap), anything else Assimp reads (importWithAssimp). Faces become convex patches by
/// the rules of face_to_patches.h; `Scene::report` tells what happened to them. Throws InputError
/// (naming file and line) on unreadable or malformed input, non-finite coordinates, bad indices,
/// faces with fewer than 3 vertices, or a scene with no usable face.
Scene loadScene(const std::string& path);

/// loadScene, then, when `contactSplit`, splitPatchesAtContacts (scene/contact_split.h): what
/// `radiosity` and `photons` read by default and `vis --contact-split`.
Scene loadScene(const std::string& path, bool contactSplit);

/// Reads Wavefront OBJ with its MTL libraries (looked up beside the OBJ). A missing MTL gives a
/// warning and grey 0.5 without emission; a present but unreadable or malformed MTL is an error.
Scene importObj(const std::string& path);

/// importObj on text already read; `path` names it in messages and locates its MTL libraries.
Scene importObjText(const std::string& path, const std::string& text);

/// Reads a mesh through Assimp (PLY, glTF/GLB, ...): node transforms applied, every polygon a face
/// (front = counter-clockwise side, as glTF), material diffuse / glTF base colour → Kd, emissive
/// → Ke, no material → grey 0.5. Points and lines are skipped with a warning. Throws InputError
/// naming the file when Assimp cannot read it or no usable face is left.
Scene importWithAssimp(const std::string& path);

/// True when Assimp has a reader for `extension` (with its dot, e.g. ".ply").
bool assimpReadsExtension(const std::string& extension);

/// Writes the patches as OBJ (face k = patch k, vertices counter-clockwise seen from the front)
/// and its MTL beside it (same name, .mtl), one material per scene material with Kd and Ke.
/// Throws InputError when a file cannot be written.
void writeObj(const Scene& scene, const std::string& objPath);

}  // namespace gv
