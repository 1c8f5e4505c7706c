// The shared Quake maps (ericw-tools test maps, LibreQuake): every one converts, and a closed
// map's playable air, found through BSP portals from the player start, is sealed from the void.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>

#include "bsp/subdivision.h"
#include "quake/brush_csg.h"
#include "quake/map_to_scene.h"

namespace gv {
namespace {

const std::string kQuakeDir = std::string(GV_SHARED_DATA_DIR) + "/quake/";

Vec3 originOf(const MapFile& map, const std::string& className) {
  for (const MapEntity& e : map.entities)
    if (e.className() == className) {
      Vec3 p;
      EXPECT_EQ(std::sscanf(e.value("origin")->c_str(), "%lf %lf %lf", &p.x, &p.y, &p.z), 3);
      return p;
    }
  ADD_FAILURE() << "no " << className;
  return {};
}

/// Cells reachable from `start` through portals.
std::vector<bool> reachable(const Subdivision& sub, uint32_t start) {
  std::vector<bool> seen(sub.cells.size(), false);
  std::deque<uint32_t> queue{start};
  seen[start] = true;
  while (!queue.empty()) {
    const uint32_t c = queue.front();
    queue.pop_front();
    for (uint32_t n : sub.neighbours(c))
      if (!seen[n]) {
        seen[n] = true;
        queue.push_back(n);
      }
  }
  return seen;
}

TEST(QuakeSharedMaps, EveryMapConverts) {
  size_t maps = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kQuakeDir)) {
    if (entry.path().extension() != ".map") continue;
    ++maps;
    const std::string path = entry.path().string();
    MapImportStats st;
    const auto t0 = std::chrono::steady_clock::now();
    const Scene s = importMap(path, {}, &st);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-22s brushes %5zu solid %5zu degenerate %3zu faces %6zu hidden %6zu cut %5zu "
                "lights %4zu patches %6zu  %.2f s\n",
                entry.path().filename().c_str(), st.brushesIn, st.solidBrushes, st.degenerateBrushes,
                st.brushFaces, st.hiddenFaces, st.cutFaces, st.lights, st.patches, seconds);
    EXPECT_GT(st.solidBrushes, 0u) << path;
    EXPECT_GT(s.emitterCount(), 0u) << path;
    // Few degenerate brushes in maps that qbsp compiled (a handful of slivers at most).
    EXPECT_LE(st.degenerateBrushes * 100, st.brushesIn) << path;
    for (const Patch& p : s.patches) ASSERT_GT(p.polygon.area(), 0) << path;
  }
  EXPECT_GE(maps, 9u);
}

void expectSealed(const std::string& name, const MapImportOptions& options) {
  const std::string path = kQuakeDir + name;
  const MapFile map = readMapFile(path);
  const Scene scene = mapToScene(map, path, options);
  const Subdivision sub = buildSubdivision(scene);
  const Vec3 start = originOf(map, "info_player_start");
  const std::vector<bool> fromStart = reachable(sub, sub.cellAt(start));
  // The void: the root box (the scene box enlarged 5 %) beyond the scene box's corners.
  const Aabb box = scene.bounds();
  const Vec3 margin = box.extent() * 0.01;
  const uint32_t outside = sub.cellAt(box.lo - margin);
  const std::vector<bool> fromOutside = reachable(sub, outside);
  size_t inside = 0, voidCells = 0;
  for (size_t c = 0; c < sub.cells.size(); ++c) {
    inside += fromStart[c];
    voidCells += fromOutside[c];
    EXPECT_FALSE(fromStart[c] && fromOutside[c]) << name << ": cell " << c << " leaks";
  }
  // The void is one connected shell around the level: all 8 corners of the root box are in it.
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner{k & 1 ? box.hi.x + margin.x : box.lo.x - margin.x,
                      k & 2 ? box.hi.y + margin.y : box.lo.y - margin.y,
                      k & 4 ? box.hi.z + margin.z : box.lo.z - margin.z};
    EXPECT_TRUE(fromOutside[sub.cellAt(corner)]) << name << " corner " << k;
  }
  EXPECT_GT(inside, 10u) << name;
  // The air never enters a solid: no cell reachable from the start has its centroid inside a
  // solid brush (an independent test against the brushes' planes, not the patches).
  const Tolerance tol = scene.tolerance();
  std::vector<BrushSolid> solids;
  for (const MapEntity& e : map.entities) {
    const std::string c = e.className();
    if (c != "worldspawn" && c != "func_group" && c != "func_detail") continue;
    for (const MapBrush& b : e.brushes) {
      bool plain = true;
      for (const MapBrushSide& sd : b.sides)
        plain = plain && sd.texture.find_first_of("*") == std::string::npos && sd.texture != "clip" &&
                sd.texture.rfind("hint", 0) != 0 && sd.texture != "skip" && sd.texture != "trigger" &&
                sd.texture != "origin";
      if (std::optional<BrushSolid> s = plain ? brushSolid(b, tol) : std::nullopt) solids.push_back(*s);
    }
  }
  size_t inSolid = 0;
  for (size_t c = 0; c < sub.cells.size(); ++c) {
    if (!fromStart[c]) continue;
    const Vec3 p = sub.cells[c].shape.centroid();
    for (const BrushSolid& s : solids) {
      bool in = true;
      for (const Plane& h : s.shape.halfspaces) in = in && h.distance(p) < -tol.planeOffset();
      if (in) {
        ++inSolid;
        break;
      }
    }
  }
  EXPECT_EQ(inSolid, 0u) << name << ": cells reachable from the start inside solids";
  std::printf("%s: %zu patches, %zu cells, %zu portals; %zu cells reachable from the player start, "
              "%zu in the void\n",
              name.c_str(), scene.patches.size(), sub.cells.size(), sub.portals.size(), inside, voidCells);
}

TEST(QuakeSharedMaps, DISABLED_SealedFromEnv) {
  if (const char* name = std::getenv("GV_SEAL_MAP")) expectSealed(name, {});
}

TEST(QuakeSharedMaps, QbspfeaturesIsSealed) { expectSealed("qbspfeatures.map", {}); }

TEST(QuakeSharedMaps, QbspfeaturesWithoutMoversIsSealed) {
  MapImportOptions o;
  o.includeMovers = false;
  expectSealed("qbspfeatures.map", o);
}

}  // namespace
}  // namespace gv
