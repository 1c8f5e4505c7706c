// The dispatch by extension of load_scene.h. Extensions compare case-insensitively (.OBJ, .Map).
#include "input/load_scene.h"

#include <cctype>
#include <filesystem>

#include "quake/map_to_scene.h"
#include "scene/contact_split.h"
#include "scene/scene_io.h"
#include "util/input_error.h"

namespace gv {

Scene loadScene(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".obj") return importObj(path);
  if (ext == ".map") return importMap(path);
  if (!ext.empty() && assimpReadsExtension(ext)) return importWithAssimp(path);
  throw InputError(path, 0,
                   "unsupported scene format '" + ext +
                       "' (supported: .obj, .map, and the mesh formats Assimp reads: "
                       ".ply, .gltf, .glb, ...)");
}

Scene loadScene(const std::string& path, bool contactSplit) {
  Scene scene = loadScene(path);
  if (contactSplit) splitPatchesAtContacts(scene);
  return scene;
}

}  // namespace gv
