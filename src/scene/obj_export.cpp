// Wavefront OBJ + MTL export of the patches: the `patches.obj` of the output contract
// (../shared/DESIGN.md): face k = patch k, counter-clockwise seen from the front.
#include <fmt/format.h>
#include <fmt/os.h>

#include <filesystem>
#include <set>

#include "scene/scene_io.h"
#include "util/input_error.h"

namespace gv {
namespace {

/// MTL names cannot hold whitespace; names must also be unique for `usemtl` to mean one thing.
std::vector<std::string> uniqueMaterialNames(const Scene& scene) {
  std::vector<std::string> names;
  std::set<std::string> used;
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    std::string name = scene.materials[i].name.empty() ? "material" : scene.materials[i].name;
    for (char& c : name)
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') c = '_';
    if (used.count(name)) name += fmt::format("_{}", i);
    used.insert(name);
    names.push_back(name);
  }
  return names;
}

}  // namespace

void writeObj(const Scene& scene, const std::string& objPath) {
  namespace fs = std::filesystem;
  const fs::path obj(objPath);
  const fs::path mtl = fs::path(obj).replace_extension(".mtl");
  const std::vector<std::string> names = uniqueMaterialNames(scene);
  try {
    if (obj.has_parent_path()) fs::create_directories(obj.parent_path());
    auto m = fmt::output_file(mtl.string());
    m.print("# globalvis materials: Kd = diffuse reflectance, Ke = emitted radiosity (RGB)\n");
    for (size_t i = 0; i < scene.materials.size(); ++i) {
      const Material& mat = scene.materials[i];
      m.print("newmtl {}\nKd {} {} {}\nKe {} {} {}\n\n", names[i], mat.reflectance.r,
              mat.reflectance.g, mat.reflectance.b, mat.emission.r, mat.emission.g, mat.emission.b);
    }
    m.close();

    auto o = fmt::output_file(obj.string());
    o.print("# globalvis patches: face k (0-based, file order) = patch k; front = counter-clockwise\n");
    o.print("# {} patches, {} materials\nmtllib {}\n", scene.patches.size(), scene.materials.size(),
            mtl.filename().string());
    // Shortest round-trip decimal ("{}") so that re-importing gives bit-identical coordinates.
    for (const Patch& p : scene.patches)
      for (const Vec3& v : p.polygon.vertices) o.print("v {} {} {}\n", v.x, v.y, v.z);
    size_t next = 1;
    uint32_t current = UINT32_MAX;
    for (const Patch& p : scene.patches) {
      if (p.material != current) {
        current = p.material;
        o.print("usemtl {}\n", names.at(current));
      }
      o.print("f");
      for (size_t k = 0; k < p.polygon.vertices.size(); ++k) o.print(" {}", next++);
      o.print("\n");
    }
    o.close();
  } catch (const std::system_error& e) {  // also fs::filesystem_error
    throw InputError(objPath, 0, std::string("cannot write: ") + e.what());
  }
}

}  // namespace gv
