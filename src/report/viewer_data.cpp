// Building the viewer's embedded JSON from a run's files (see viewer_data.h).
#include "report/viewer_data.h"

#include <cmath>
#include <optional>

#include "report/piece_radiosity.h"
#include "scene/patches_obj.h"
#include "scene/scene_io.h"
#include "util/input_error.h"
#include "visibility/visibility_graph.h"

namespace gv {
namespace {

using nlohmann::json;

/// Coordinates are written to this fraction of the scene diagonal: far below a pixel at any
/// zoom the viewer allows, and it keeps numbers short.
constexpr double kRelativeCoordinateQuantum = 1e-6;

/// Rounds to a power of ten near `quantum`, dividing by its exact inverse so that the shortest
/// decimal of the result is short (no 0.30000000000000004).
struct Rounder {
  double scale = 1;  ///< 10^k >= 1 / quantum
  explicit Rounder(double quantum) {
    scale = std::pow(10.0, std::ceil(-std::log10(quantum > 0 ? quantum : 1.0)));
  }
  double operator()(double x) const { return std::round(x * scale) / scale; }
};

void addPolygon(json& packed, const std::vector<Vec3>& vertices, const Rounder& round) {
  packed["sizes"].push_back(vertices.size());
  json& xyz = packed["xyz"];
  for (const Vec3& v : vertices) {
    xyz.push_back(round(v.x));
    xyz.push_back(round(v.y));
    xyz.push_back(round(v.z));
  }
}

json emptyPolygons() {
  return {{"sizes", json::array()}, {"xyz", json::array()}};
}

json rgbJson(const Rgb& c) {
  return json::array({c.r, c.g, c.b});
}

}  // namespace

json viewerDataJson(const RunFiles& files, const std::string& title,
                    const ViewerDataOptions& options) {
  if (files.patchesObj.empty())
    throw InputError(files.dir.string(), 0,
                     "no patches.obj here or in vis/ or radiosity/ (run `globalvis vis` or "
                     "`globalvis radiosity` with -o into this directory first)");
  const std::string patchesPath = files.patchesObj.string();
  const Scene scene = importPatchesObj(patchesPath, "globalvis");
  const Aabb bounds = scene.bounds();
  const Rounder round(kRelativeCoordinateQuantum * bounds.diagonal());

  json data = {{"format", "globalvis-viewer-1"},
               {"title", title},
               {"sources", {{"patches", patchesPath}}},
               {"notes", json::array()},
               {"bounds",
                {{"min", {bounds.lo.x, bounds.lo.y, bounds.lo.z}},
                 {"max", {bounds.hi.x, bounds.hi.y, bounds.hi.z}}}}};
  json patches = emptyPolygons();
  patches["material"] = json::array();
  for (const Patch& p : scene.patches) {
    addPolygon(patches, p.polygon.vertices, round);
    patches["material"].push_back(p.material);
  }
  data["patches"] = std::move(patches);
  json materials = json::array();
  for (const Material& m : scene.materials)
    materials.push_back(
        {{"name", m.name}, {"kd", rgbJson(m.reflectance)}, {"ke", rgbJson(m.emission)}});
  data["materials"] = std::move(materials);

  data["pairs"] = nullptr;
  if (!files.visibilityTxt.empty()) {
    const std::string path = files.visibilityTxt.string();
    const VisibilityGraph graph = readVisibilityTxt(path);
    size_t entries = 0;
    for (const Interaction& in : graph.interactions) entries += in.blockers.size();
    const bool embedBlockers = entries <= options.maxBlockerEntries;
    json pairs = {{"s", json::array()},
                  {"r", json::array()},
                  {"blockerCounts", json::array()},
                  {"blockers", json::array()},
                  {"blockersEmbedded", embedBlockers}};
    if (!embedBlockers)
      data["notes"].push_back(
          path + " has " + std::to_string(entries) +
          " blocker entries, more than the page embeds: blocker lists left out");
    for (const Interaction& in : graph.interactions) {
      if (in.r >= scene.patches.size())
        throw InputError(path, 0,
                         "pair " + std::to_string(in.s) + " " + std::to_string(in.r) +
                             " names a patch that patches.obj does not have");
      pairs["s"].push_back(in.s);
      pairs["r"].push_back(in.r);
      pairs["blockerCounts"].push_back(in.blockers.size());
      for (uint32_t b : in.blockers) {
        if (b >= scene.patches.size())
          throw InputError(path, 0, "blocker " + std::to_string(b) + " is not a patch");
        if (embedBlockers) pairs["blockers"].push_back(b);
      }
    }
    data["pairs"] = std::move(pairs);
    data["sources"]["visibility"] = path;
  }

  data["radiosity"] = nullptr;
  data["elements"] = nullptr;
  if (!files.radiosityTxt.empty()) {
    std::optional<std::vector<Rgb>> perPatch;
    if (files.radiosityPatchesObj.empty()) {
      perPatch = readRadiosityTxt(files.radiosityTxt.string(), scene.patches.size());
    } else {
      // radiosity.txt is per patch of the radiosity run's own patches (cut along contacts).
      // A file this tool wrote: read back face for face, slivers kept (scene/patches_obj.h).
      const Scene pieces = importObj(files.radiosityPatchesObj.string(), /*keepSlivers=*/true);
      perPatch = radiosityOnPatches(
          scene, pieces, readRadiosityTxt(files.radiosityTxt.string(), pieces.patches.size()));
      if (!perPatch)
        data["notes"].push_back(files.radiosityPatchesObj.string() + " is not " + patchesPath +
                                " cut into pieces: radiosity.txt is not shown per patch");
    }
    if (perPatch) {
      json flat = json::array();
      for (const Rgb& b : *perPatch) {
        flat.push_back(b.r);
        flat.push_back(b.g);
        flat.push_back(b.b);
      }
      data["radiosity"] = std::move(flat);
      data["sources"]["radiosity"] = files.radiosityTxt.string();
    }
  }
  if (!files.elementsPly.empty()) {
    const ElementMesh mesh = readElementsPly(files.elementsPly.string());
    if (mesh.positions.size() <= options.maxElementVertices) {
      json elements = {{"xyz", json::array()},
                       {"rgb", json::array()},
                       {"faceSizes", json::array()},
                       {"faceIndices", json::array()}};
      for (size_t v = 0; v < mesh.positions.size(); ++v) {
        for (double x : {mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z})
          elements["xyz"].push_back(round(x));
        for (int c : mesh.colors[v]) elements["rgb"].push_back(c);
      }
      for (const std::vector<uint32_t>& f : mesh.faces) {
        elements["faceSizes"].push_back(f.size());
        for (uint32_t i : f) elements["faceIndices"].push_back(i);
      }
      data["elements"] = std::move(elements);
      data["sources"]["elements"] = files.elementsPly.string();
    } else {
      data["notes"].push_back(files.elementsPly.string() + " has " +
                              std::to_string(mesh.positions.size()) +
                              " vertices, more than the page embeds: patches are shaded by "
                              "radiosity.txt instead");
    }
  }

  data["cells"] = nullptr;
  data["cellCount"] = 0;
  if (!files.cellsObj.empty()) {
    const std::string path = files.cellsObj.string();
    json cells = emptyPolygons();
    cells["cell"] = json::array();
    long cellCount = 0;
    for (const NamedPolygon& p : readObjPolygons(path)) {
      const long cell = groupNumbers(p.group, 1, path)[0];
      addPolygon(cells, p.vertices, round);
      cells["cell"].push_back(cell);
      cellCount = std::max(cellCount, cell + 1);
    }
    data["cells"] = std::move(cells);
    data["cellCount"] = cellCount;
    data["sources"]["cells"] = path;
  }
  data["portals"] = nullptr;
  if (!files.portalsObj.empty()) {
    const std::string path = files.portalsObj.string();
    json portals = emptyPolygons();
    portals["cells"] = json::array();
    for (const NamedPolygon& p : readObjPolygons(path)) {
      const std::vector<long> n = groupNumbers(p.group, 3, path);  // portal_k_back_front
      addPolygon(portals, p.vertices, round);
      portals["cells"].push_back(n[1]);
      portals["cells"].push_back(n[2]);
    }
    data["portals"] = std::move(portals);
    data["sources"]["portals"] = path;
  }
  return data;
}

}  // namespace gv
