// Reading and writing scenes: Wavefront OBJ + MTL (Kd = reflectance, Ke = emission) and the mesh
// formats Assimp reads. Choosing among the importers by extension is input/load_scene.h's job.
#pragma once

#include <string>

#include "scene/scene.h"

namespace gv {

/// Reads Wavefront OBJ with its MTL libraries (looked up beside the OBJ). A missing MTL gives a
/// warning and grey 0.5 without emission; a present but unreadable or malformed MTL is an error.
/// `keepSlivers`: keep faces thinner than the model tolerance (faceToPatches), for files this
/// tool wrote (scene/patches_obj.h).
Scene importObj(const std::string& path, bool keepSlivers = false);

/// importObj on text already read; `path` names it in messages and locates its MTL libraries.
Scene importObjText(const std::string& path, const std::string& text, bool keepSlivers = false);

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
