// The shared Quake maps (ericw-tools test maps, LibreQuake): every one converts, and each map's
// playable air, found through BSP portals from a player start, is sealed from the void around it.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "bsp/bsp_oracle.h"
#include "bsp/subdivision.h"
#include "quake/brush_csg.h"
#include "quake/map_text.h"
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

using bsptest::reachable;

struct SealReport {
  size_t cells = 0, portals = 0;
  size_t fromStart = 0;       ///< cells reachable from the start point
  size_t voidCells = 0;       ///< cells reachable from outside the scene box
  size_t leaking = 0;         ///< cells reachable from both
  size_t inSolid = 0;         ///< cells reachable from the start whose centroid is inside a brush
  bool voidConnected = true;  ///< all 8 corners of the root box reached from one of them
};

/// Builds the BSP of the converted map and walks its portals from `start` and from the void.
/// "Inside a brush" is tested against the plain world brushes' planes (independent of the
/// patches): worldspawn, func_group and func_detail brushes without special textures.
SealReport seal(const MapFile& map, const Scene& scene, const Vec3& start) {
  const Subdivision sub = buildSubdivision(scene);
  SealReport r;
  r.cells = sub.cells.size();
  r.portals = sub.portals.size();
  const std::vector<bool> fromStart = reachable(sub, sub.cellAt(start));
  const Aabb box = scene.bounds();
  const Vec3 margin = box.extent() * 0.01;  // inside the root box (the scene box + 5 %)
  const std::vector<bool> fromVoid = reachable(sub, sub.cellAt(box.lo - margin));
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner{k & 1 ? box.hi.x + margin.x : box.lo.x - margin.x,
                      k & 2 ? box.hi.y + margin.y : box.lo.y - margin.y,
                      k & 4 ? box.hi.z + margin.z : box.lo.z - margin.z};
    r.voidConnected = r.voidConnected && fromVoid[sub.cellAt(corner)];
  }
  const Tolerance tol = scene.tolerance();
  std::vector<BrushSolid> solids;
  for (const MapEntity& e : map.entities) {
    const std::string c = e.className();
    if (c != "worldspawn" && c != "func_group" && c != "func_detail") continue;
    for (const MapBrush& b : e.brushes) {
      bool plain = true;
      for (const MapBrushSide& sd : b.sides)
        plain = plain && sd.texture.find('*') == std::string::npos && sd.texture != "clip" &&
                sd.texture.rfind("hint", 0) != 0 && sd.texture != "skip" &&
                sd.texture != "trigger" && sd.texture != "origin";
      if (!plain) continue;
      if (std::optional<BrushSolid> s = brushSolid(b, tol)) solids.push_back(std::move(*s));
    }
  }
  for (size_t c = 0; c < sub.cells.size(); ++c) {
    r.fromStart += fromStart[c];
    r.voidCells += fromVoid[c];
    r.leaking += fromStart[c] && fromVoid[c];
    if (!fromStart[c]) continue;
    const Vec3 p = sub.cells[c].shape.centroid();
    for (const BrushSolid& s : solids) {
      bool in = true;
      for (const Plane& h : s.shape.halfspaces) in = in && h.distance(p) < -tol.planeOffset();
      if (in) {
        ++r.inSolid;
        break;
      }
    }
  }
  return r;
}

SealReport sealOfSharedMap(const std::string& name, const std::string& startClass,
                           const MapImportOptions& options = {}) {
  const std::string path = kQuakeDir + name;
  const MapFile map = readMapFile(path);
  const Scene scene = mapToScene(map, path, options);
  const SealReport r = seal(map, scene, originOf(map, startClass));
  std::printf(
      "%-22s %6zu patches %6zu cells %6zu portals: %5zu cells reachable from %s, %5zu in "
      "the void, %zu leaking, %zu inside solids\n",
      name.c_str(), scene.patches.size(), r.cells, r.portals, r.fromStart, startClass.c_str(),
      r.voidCells, r.leaking, r.inSolid);
  return r;
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
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf(
        "%-22s brushes %5zu solid %5zu degenerate %3zu faces %6zu hidden %6zu cut %5zu "
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

TEST(QuakeSharedMaps, TheSealCheckFindsAHole) {
  // A hollow room of six 16-unit walls around the air [0, 256]^3 is sealed; without its +x wall
  // the start reaches the void. (Checks the checker on a case with a known answer.)
  const std::vector<std::pair<Vec3, Vec3>> walls = {
      {{-16, -16, -16}, {0, 272, 272}}, {{256, -16, -16}, {272, 272, 272}},
      {{0, -16, -16}, {256, 0, 272}},   {{0, 256, -16}, {256, 272, 272}},
      {{0, 0, -16}, {256, 256, 0}},     {{0, 0, 256}, {256, 256, 272}}};
  for (bool open : {false, true}) {
    std::string brushes;
    for (size_t i = 0; i < walls.size(); ++i)
      if (!(open && i == 1)) brushes += test::boxBrush(walls[i].first, walls[i].second);
    const std::string text = test::world(brushes) +
                             test::pointEntity("info_player_start", {128, 128, 64}) +
                             test::pointEntity("light", {128, 128, 200});
    const MapFile map = parseMapText("room.map", text);
    const Scene scene = mapToScene(map, "room.map");
    const SealReport r = seal(map, scene, {128, 128, 64});
    EXPECT_TRUE(r.voidConnected);
    EXPECT_EQ(r.leaking > 0, open);
    EXPECT_EQ(r.inSolid, 0u);
  }
}

TEST(QuakeSharedMaps, SmallMapsAreSealedAndTheAirStaysOutOfSolids) {
  for (bool movers : {true, false}) {
    MapImportOptions o;
    o.includeMovers = movers;
    for (const char* name : {"qbspfeatures.map", "light_general.map", "lqdm13.map"}) {
      const SealReport r = sealOfSharedMap(name, "info_player_start", o);
      EXPECT_TRUE(r.voidConnected) << name;
      EXPECT_EQ(r.leaking, 0u) << name;
      EXPECT_EQ(r.inSolid, 0u) << name;
      EXPECT_GT(r.fromStart, 100u) << name;
    }
  }
}

TEST(QuakeSharedMaps, LargeMapsAreSealed) {
  // lq_e1m8's info_player_start is a closed sky closet (the level starts by teleporting out), so
  // a deathmatch start seeds the air there. lq_e1m8 has cracks into solids, no leak: slanted
  // off-grid brushes meet leaving slivers (0.002-0.015 units wide) thinner than the model
  // tolerance, which the BSP keeps as portals into brush interiors. Counted here, not required
  // to be zero (docs/BENCHMARKS.md).
  const std::vector<std::tuple<const char*, const char*, bool>> maps = {
      {"E1M1-edited-ents.map", "info_player_start", true},
      {"base1-test.map", "info_player_start", true},
      {"retrojam1_ericw.map", "info_player_start", true},
      {"lq_e1m8.map", "info_player_deathmatch", false},
      {"lq_e2m3.map", "info_player_start", true},
      {"e3m4.map", "info_player_start", true},
      {"lq_e4m4.map", "info_player_start", true}};
  for (const auto& [name, start, airOutOfSolids] : maps) {
    const SealReport r = sealOfSharedMap(name, start);
    EXPECT_TRUE(r.voidConnected) << name;
    EXPECT_EQ(r.leaking, 0u) << name;
    if (airOutOfSolids) {
      EXPECT_EQ(r.inSolid, 0u) << name;
    }
    EXPECT_GT(r.fromStart, 10u) << name;
  }
}

}  // namespace
}  // namespace gv
