// Mesh formats other than OBJ (PLY, glTF/GLB, and whatever else Assimp reads) through Assimp:
// polygons → faces → convex patches (face_to_patches.h); material colours → Kd and Ke.
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "scene/face_to_patches.h"
#include "scene/read_file.h"
#include "scene/scene_io.h"
#include "util/input_error.h"

namespace gv {
namespace {

Rgb colourOf(const aiMaterial& m, const char* key, unsigned type, unsigned index, Rgb fallback) {
  aiColor4D c;
  if (m.Get(key, type, index, c) != AI_SUCCESS) return fallback;
  return {c.r, c.g, c.b};
}

}  // namespace

bool assimpReadsExtension(const std::string& extension) {
  Assimp::Importer importer;
  return importer.IsExtensionSupported(extension);
}

Scene importWithAssimp(const std::string& path) {
  (void)readWholeFile(path);  // the same missing / directory / unreadable messages as OBJ
  Assimp::Importer importer;
  // Node transforms baked into the vertices; no triangulation (the patch rules decide), points
  // and lines dropped by sorting primitive types apart and skipping them below.
  const aiScene* ai =
      importer.ReadFile(path, aiProcess_PreTransformVertices | aiProcess_JoinIdenticalVertices |
                                  aiProcess_SortByPType);
  if (!ai || (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !ai->mRootNode)
    throw InputError(path, 0,
                     std::string("cannot be read as a mesh: ") + importer.GetErrorString());

  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool isPly = ext == ".ply";
  Scene scene;
  for (unsigned i = 0; i < ai->mNumMaterials; ++i) {
    const aiMaterial& m = *ai->mMaterials[i];
    aiString name;
    m.Get(AI_MATKEY_NAME, name);
    // glTF's base colour is the diffuse reflectance; Assimp copies it to "diffuse" for some
    // importers only, so prefer it when present.
    // Formats without materials get a material Assimp made up (PLY: white, unnamed; others
    // AI_DEFAULT_MATERIAL_NAME): grey 0.5 without emission instead, as OBJ without MTL.
    const bool none = std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME || isPly;
    const Rgb kd = none ? Rgb{0.5, 0.5, 0.5}
                        : colourOf(m, AI_MATKEY_BASE_COLOR,
                                   colourOf(m, AI_MATKEY_COLOR_DIFFUSE, {0.5, 0.5, 0.5}));
    const Rgb ke = none ? Rgb{} : colourOf(m, AI_MATKEY_COLOR_EMISSIVE, {});
    scene.addMaterial(
        {name.length > 0 ? std::string(name.C_Str()) : "material_" + std::to_string(i), kd, ke});
  }
  uint32_t defaultMaterial = UINT32_MAX;

  Aabb box;
  for (unsigned k = 0; k < ai->mNumMeshes; ++k) {
    const aiMesh& mesh = *ai->mMeshes[k];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw InputError(path, 0,
                         "mesh " + std::to_string(k) + " vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
      box.add(Vec3{p.x, p.y, p.z});
    }
  }
  const Tolerance tol = Tolerance::forBounds(box);

  ImportReport& report = scene.report;
  uint32_t faceIndex = 0;
  size_t pointsAndLines = 0;
  for (unsigned k = 0; k < ai->mNumMeshes; ++k) {
    const aiMesh& mesh = *ai->mMeshes[k];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices < 3) {
        ++pointsAndLines;
        continue;
      }
      const uint32_t index = faceIndex++;
      ++report.facesIn;
      std::vector<Vec3> polygon;
      polygon.reserve(face.mNumIndices);
      for (unsigned j = 0; j < face.mNumIndices; ++j) {
        const aiVector3D& p = mesh.mVertices[face.mIndices[j]];
        polygon.push_back({p.x, p.y, p.z});
      }
      const FacePatches converted = faceToPatches(polygon, tol);
      if (!countFaceOutcome(converted.outcome, report)) continue;
      uint32_t material = mesh.mMaterialIndex;
      if (material >= scene.materials.size()) {
        if (defaultMaterial == UINT32_MAX)
          defaultMaterial = scene.addMaterial({"default_grey", {0.5, 0.5, 0.5}, {}});
        material = defaultMaterial;
      }
      for (const ConvexPolygon& piece : converted.pieces)
        scene.patches.push_back({piece, material, index});
    }
  }
  if (pointsAndLines > 0)
    report.warnings.push_back(path + ": " + std::to_string(pointsAndLines) +
                              " point / line primitive(s) skipped (not surfaces)");
  if (scene.patches.empty())
    throw InputError(path, 0,
                     report.facesIn == 0 ? "the scene has no faces"
                                         : "the scene has no usable face (all " +
                                               std::to_string(report.facesIn) + " are degenerate)");
  return scene;
}

}  // namespace gv
