// Wavefront OBJ + MTL import through tinyobjloader (double precision build), after a precheck
// that gives bad input a file:line message. Faces become convex patches (face_to_patches.h).
#include <tiny_obj_loader.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "scene/face_to_patches.h"
#include "scene/obj_precheck.h"
#include "scene/read_file.h"
#include "scene/scene_io.h"
#include "util/input_error.h"

namespace gv {
namespace fs = std::filesystem;
namespace {

/// Checks each referenced MTL library and returns their concatenated text. Missing → warning
/// (grey default); present but unreadable or malformed → InputError.
std::string readMaterialLibraries(const std::string& objPath, const std::vector<MtlReference>& libs,
                                  ImportReport& report) {
  std::string all;
  const fs::path dir = fs::path(objPath).parent_path();
  for (const MtlReference& lib : libs) {
    const fs::path mtl = dir / lib.name;
    std::error_code ec;
    if (!fs::exists(mtl, ec)) {
      report.warnings.push_back(objPath + ":" + std::to_string(lib.line) + ": material library '" +
                                lib.name +
                                "' not found; its materials become grey 0.5 without emission");
      continue;
    }
    std::string text;
    try {
      text = readWholeFile(mtl.string());
    } catch (const InputError& e) {
      throw InputError(objPath, lib.line, std::string("material library unreadable: ") + e.what());
    }
    for (std::string& w : precheckMtl(mtl.string(), text)) report.warnings.push_back(std::move(w));
    all += text;
    all += '\n';
  }
  return all;
}

Rgb toRgb(const tinyobj::real_t c[3]) {
  return {c[0], c[1], c[2]};
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

}  // namespace

Scene importObj(const std::string& path, bool keepSlivers) {
  return importObjText(path, readWholeFile(path), keepSlivers);
}

Scene importObjText(const std::string& path, const std::string& text, bool keepSlivers) {
  Scene scene;
  const ObjPrecheck pre = precheckObj(path, text);
  const std::string mtlText = readMaterialLibraries(path, pre.libraries, scene.report);

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;  // keep polygons: the patch rules decide about splitting
  config.vertex_color = false;
  config.mtl_search_path = fs::path(path).parent_path().string();
  tinyobj::ObjReader reader;
  // With MTL text given, tinyobjloader resolves every `usemtl` against it (all libraries at once).
  if (!reader.ParseFromString(text, mtlText, config))
    throw InputError(path, 0, "OBJ parse error: " + reader.Error());
  std::set<std::string> seen;  // tinyobjloader repeats a warning at every `usemtl`
  for (const std::string& w : splitLines(reader.Warning()))
    if (w.find("not found") != std::string::npos && seen.insert(w).second)
      scene.report.warnings.push_back(path + ": " + w + " (grey 0.5 used)");
  const std::vector<tinyobj::material_t>& materials = reader.GetMaterials();

  for (const tinyobj::material_t& m : materials)
    scene.addMaterial({m.name, toRgb(m.diffuse), toRgb(m.emission)});
  uint32_t defaultMaterial = UINT32_MAX;  // added on first use

  Aabb box;
  for (const Vec3& p : pre.vertices) box.add(p);
  const Tolerance tol = Tolerance::forBounds(box);

  uint32_t faceIndex = 0;
  ImportReport& report = scene.report;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t offset = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f, ++faceIndex) {
      const size_t count = mesh.num_face_vertices[f];
      std::vector<Vec3> face;
      face.reserve(count);
      for (size_t k = 0; k < count; ++k) {
        // tinyobjloader numbers vertices in file order, as the precheck does; should the two
        // readers ever disagree, that is still bad input, never a crash.
        const auto vi = static_cast<size_t>(mesh.indices[offset + k].vertex_index);
        if (vi >= pre.vertices.size())
          throw InputError(path, 0,
                           "face " + std::to_string(faceIndex + 1) + " refers to vertex " +
                               std::to_string(vi + 1) + " of " +
                               std::to_string(pre.vertices.size()));
        face.push_back(pre.vertices[vi]);
      }
      offset += count;
      ++report.facesIn;
      const FacePatches converted = faceToPatches(face, tol, keepSlivers);
      if (!countFaceOutcome(converted.outcome, report)) continue;
      const int mid = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
      uint32_t material;
      if (mid >= 0 && static_cast<size_t>(mid) < materials.size()) {
        material = static_cast<uint32_t>(mid);
      } else {
        if (defaultMaterial == UINT32_MAX)
          defaultMaterial = scene.addMaterial({"default_grey", {0.5, 0.5, 0.5}, {}});
        material = defaultMaterial;
      }
      for (const ConvexPolygon& piece : converted.pieces)
        scene.patches.push_back({piece, material, faceIndex});
    }
  }
  if (scene.patches.empty())
    throw InputError(path, 0,
                     report.facesIn == 0 ? "the scene has no faces"
                                         : "the scene has no usable face (all " +
                                               std::to_string(report.facesIn) + " are degenerate)");
  return scene;
}

}  // namespace gv
