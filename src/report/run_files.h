// Reading the files a pipeline run wrote (cells.obj, portals.obj, visibility.txt, radiosity.txt,
// elements.ply, stats.json) back for the viewer and the report; the layout of a run directory.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geometry/vec3.h"
#include "scene/scene.h"

namespace gv {

/// Where a run's outputs are. `globalvis view DIR` and `globalvis report DIR` look in DIR/vis,
/// DIR/cells and DIR/radiosity (what `make run` writes), then in DIR itself; an empty path
/// means "not present".
struct RunFiles {
  std::filesystem::path dir;
  std::filesystem::path patchesObj;  ///< vis/patches.obj, else radiosity/patches.obj
  std::filesystem::path visibilityTxt;
  std::filesystem::path cellsObj, portalsObj;
  std::filesystem::path radiosityTxt, elementsPly;
  /// The patches radiosity.txt is per patch of (radiosity/patches.obj, cut along contacts), when
  /// it is not `patchesObj`.
  std::filesystem::path radiosityPatchesObj;
  std::filesystem::path cellsStats, visStats, radiosityStats;  ///< each stage's stats.json
};

/// Finds the files of a run under `dir`; throws InputError if `dir` is not a directory.
RunFiles findRunFiles(const std::filesystem::path& dir);

/// A polygon of an OBJ file with the name of the group (`g`) it is in.
struct NamedPolygon {
  std::string group;
  std::vector<Vec3> vertices;
};

/// Reads the faces of an OBJ file (v, f, g records; others ignored) in file order. Throws
/// InputError with file:line on malformed numbers or bad vertex indices.
std::vector<NamedPolygon> readObjPolygons(const std::string& path);

/// The integers after the first `_` of a group name `prefix_a_b_c`: {a, b, c}. Throws
/// InputError (naming `path`) when the name does not have `count` of them.
std::vector<long> groupNumbers(const std::string& group, size_t count, const std::string& path);

/// radiosity.txt: per patch (in patch order) its linear RGB radiosity. Throws InputError on
/// malformed lines, ids out of order, or a count different from `patchCount`.
std::vector<Rgb> readRadiosityTxt(const std::string& path, size_t patchCount);

/// The leaf-element mesh of elements.ply: shared vertices with display colours (0..255).
struct ElementMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> colors;
  std::vector<std::vector<uint32_t>> faces;
};

/// Reads an ASCII PLY with vertex properties x, y, z, red, green, blue (others skipped) and a
/// face list `vertex_indices`. Throws InputError with file:line when it is malformed.
ElementMesh readElementsPly(const std::string& path);

/// Parses a stats.json; std::nullopt for an empty path. Throws InputError when unreadable.
std::optional<nlohmann::json> readStatsJson(const std::filesystem::path& path);

}  // namespace gv
