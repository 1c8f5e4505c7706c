// `globalvis info SCENE`: a newcomer's first look at a scene (counts, bounds, area).
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/scene_input.h"

namespace gv::cli {
namespace {

nlohmann::json infoJson(const std::string& path, const Scene& s) {
  const Aabb box = s.bounds();
  const ImportReport& r = s.report;
  return {{"scene", path},
          {"faces_in", r.facesIn},
          {"patches", s.patches.size()},
          {"dropped_degenerate", r.droppedDegenerate},
          {"split_non_convex", r.splitNonConvex},
          {"triangulated_non_planar", r.triangulatedNonPlanar},
          {"split_at_contacts", r.splitAtContacts},
          {"contact_pieces", r.contactPieces},
          {"hidden_dropped", r.hiddenDropped},
          {"coincident_dropped", r.coincidentDropped},
          {"partly_hidden_kept", r.partlyHiddenKept},
          {"front_beyond_air", r.frontBeyondAir},
          {"air_inside_shells", r.shells},
          {"materials", s.materials.size()},
          {"emitters", s.emitterCount()},
          {"bounds_min", {box.lo.x, box.lo.y, box.lo.z}},
          {"bounds_max", {box.hi.x, box.hi.y, box.hi.z}},
          {"total_area", s.totalArea()},
          {"warnings", r.warnings}};
}

void printInfo(const std::string& path, const Scene& s) {
  const Aabb box = s.bounds();
  const Vec3 size = box.extent();
  const ImportReport& r = s.report;
  for (const std::string& w : r.warnings) fmt::print(stderr, "warning: {}\n", w);
  fmt::print("scene        {}\n", path);
  fmt::print("faces in     {}\n", r.facesIn);
  fmt::print("patches      {}  (non-convex faces split: {}, non-planar faces triangulated: {})\n",
             s.patches.size(), r.splitNonConvex, r.triangulatedNonPlanar);
  fmt::print("contacts     {} patches cut along patches resting on them, into {} pieces\n",
             r.splitAtContacts, r.contactPieces);
  fmt::print("dropped      {} degenerate faces\n", r.droppedDegenerate);
  fmt::print(
      "hidden       {} patches inside closed solids or covered by same-facing twins "
      "dropped ({} twins), {} partly hidden kept whole\n",
      r.hiddenDropped + r.coincidentDropped, r.coincidentDropped, r.partlyHiddenKept);
  fmt::print("beyond air   {} patches whose front looks partly out of the air ({})\n",
             r.frontBeyondAir,
             r.shells ? "air inside inward-facing shells: the outside counts"
                      : "air outside closed solids: their insides count");
  fmt::print("materials    {}\n", s.materials.size());
  fmt::print("emitters     {} patches\n", s.emitterCount());
  fmt::print("bounds       ({:g}, {:g}, {:g}) to ({:g}, {:g}, {:g}), size {:g} x {:g} x {:g}\n",
             box.lo.x, box.lo.y, box.lo.z, box.hi.x, box.hi.y, box.hi.z, size.x, size.y, size.z);
  fmt::print("total area   {:g}\n", s.totalArea());
}

}  // namespace

Action addInfoCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("info",
                                 "Print a scene's counts: faces in, patches out, dropped "
                                 "faces, emitters, bounding box, total area");
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option(
         "scene", *path,
         "Scene file (.obj with .mtl, Quake .map, or a mesh Assimp reads: .ply, .gltf, .glb ...)")
      ->required();
  cmd->add_flag("--json", *json, "Print JSON instead of text");
  return [path, json] {
    const Scene scene = loadPipelineScene(*path, {});
    if (*json)
      fmt::print("{}\n", infoJson(*path, scene).dump(2));
    else
      printInfo(*path, scene);
    return 0;
  };
}

}  // namespace gv::cli
