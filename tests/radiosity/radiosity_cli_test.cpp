// `globalvis radiosity` end to end: an emitter over a receiver through OBJ/MTL files, checked
// against ρ E F with F from Howell's catalogue (C-11), and the output contract of DESIGN.md.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "report/run_files.h"
#include "scene/scene_io.h"
#include "support/howell_pair.h"
#include "support/run_cli.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

TEST(RadiosityCliTest, EmitterOverReceiverGivesRhoEF) {
  const auto dir = test::scratchDir();
  const auto scene = test::writeHowellPair(dir);
  for (const std::string mode : {"rays", "shaft"}) {
    SCOPED_TRACE(mode);
    const auto out = dir / ("out_" + mode);
    const test::CliResult r = test::runCli("radiosity '" + scene.string() + "' -o '" +
                                           out.string() + "' -q --visibility " + mode);
    ASSERT_EQ(r.exitCode, 0) << r.output;

    std::ifstream txt(out / "radiosity.txt");
    ASSERT_TRUE(txt.good());
    std::vector<std::array<double, 3>> rows;
    std::string line;
    while (std::getline(txt, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream in(line);
      size_t id;
      std::array<double, 3> c{};
      in >> id >> c[0] >> c[1] >> c[2];
      ASSERT_EQ(id, rows.size());
      rows.push_back(c);
    }
    ASSERT_EQ(rows.size(), 2u);
    const double f = test::kHowellC11;
    const double rho = 0.6;
    EXPECT_NEAR(rows[0][0], rho * 3 * f, 0.02 * rho * 3 * f);
    EXPECT_NEAR(rows[0][1], rho * 2 * f, 0.02 * rho * 2 * f);
    EXPECT_NEAR(rows[0][2], rho * 1 * f, 0.02 * rho * 1 * f);
    EXPECT_DOUBLE_EQ(rows[1][0], 3.0);

    EXPECT_TRUE(std::filesystem::exists(out / "patches.obj"));
    EXPECT_TRUE(std::filesystem::exists(out / "patches.mtl"));
    EXPECT_TRUE(std::filesystem::exists(out / "elements.ply"));
    std::ifstream stats(out / "stats.json");
    const nlohmann::json j = nlohmann::json::parse(stats);
    EXPECT_EQ(j["visibility"], mode);
    EXPECT_GE(j["rounds"].size(), 1u);
    EXPECT_EQ(j["rounds"][0]["links"]["total"], 1);
    EXPECT_TRUE(j["totals"]["converged"].get<bool>());
  }
}

TEST(RadiosityCliTest, PatchesAreCutAlongContactsAndTheCoveredPartIsBlack) {
  // A 2 x 2 floor with a closed 1 x 1 x 0.5 box resting on its middle and a light panel above.
  const auto dir = test::scratchDir();
  test::writeFile(dir / "box.mtl",
                  "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl light\nKd 0 0 0\nKe 5 5 5\n");
  std::string obj = "mtllib box.mtl\nusemtl grey\n";
  obj += "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n";               // floor, facing +z
  obj += "v 0.5 0.5 0\nv 1.5 0.5 0\nv 1.5 1.5 0\nv 0.5 1.5 0\n";          // box: 5..8 bottom
  obj += "v 0.5 0.5 0.5\nv 1.5 0.5 0.5\nv 1.5 1.5 0.5\nv 0.5 1.5 0.5\n";  // 9..12 top
  obj += "f 5 8 7 6\nf 9 10 11 12\nf 5 6 10 9\nf 6 7 11 10\nf 7 8 12 11\nf 8 5 9 12\n";
  obj += "usemtl light\nv 0.5 0.5 2\nv 1.5 0.5 2\nv 1.5 1.5 2\nv 0.5 1.5 2\nf 13 16 15 14\n";
  const std::string scene = test::writeFile(dir / "box.obj", obj);

  const auto run = [&](const std::string& name, const std::string& flags) {
    const auto out = dir / name;
    const test::CliResult r = test::runCli("radiosity '" + scene + "' -o '" + out.string() +
                                           "' -q --no-pictures " + flags);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const Scene patches = importObj((out / "patches.obj").string(), /*keepSlivers=*/true);
    return std::make_pair(
        patches, readRadiosityTxt((out / "radiosity.txt").string(), patches.patches.size()));
  };
  const auto [whole, wholeB] = run("whole", "--no-contact-split");
  ASSERT_EQ(whole.patches.size(), 8u);
  const auto [cut, cutB] = run("cut", "");
  std::ifstream statsFile(dir / "cut" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(statsFile);
  EXPECT_EQ(stats["contact_split"]["patches_split"], 1);
  EXPECT_EQ(stats["contact_split"]["pieces"], 5);
  // The floor becomes four pieces around the footprint and the one under it: 12 patches.
  ASSERT_EQ(cut.patches.size(), 12u);
  double floorPower = 0, floorArea = 0;
  size_t black = 0;
  for (size_t p = 0; p < cut.patches.size(); ++p) {
    const ConvexPolygon& poly = cut.patches[p].polygon;
    if (!(std::abs(poly.centroid().z) < 1e-9 && poly.normal().z > 0.5)) continue;  // floor
    floorPower += poly.area() * cutB[p].r;
    floorArea += poly.area();
    if (std::abs(poly.area() - 1.0) < 1e-9 && length(poly.centroid() - Vec3{1, 1, 0}) < 1e-9) {
      EXPECT_EQ(cutB[p].r, 0.0);  // under the box: nothing reaches it
      ++black;
    }
  }
  EXPECT_EQ(black, 1u);
  EXPECT_NEAR(floorArea, 4.0, 1e-9);
  // Same physics either way: the floor's mean radiosity agrees (the whole floor's mesh averages
  // the covered part in, which is the error the split removes, so within a few percent).
  EXPECT_NEAR(floorPower / floorArea, wholeB[0].r, 0.03 * wholeB[0].r);
}

TEST(RadiosityCliTest, BadInputExitsTwo) {
  const auto dir = test::scratchDir();
  test::writeFile(dir / "bad.obj", "v 0 0 0\nf 1 2 3\n");
  const test::CliResult r = test::runCli("radiosity '" + (dir / "bad.obj").string() + "' -o '" +
                                         (dir / "out").string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  const test::CliResult usage = test::runCli("radiosity");
  EXPECT_EQ(usage.exitCode, 1);
}

}  // namespace
}  // namespace gv
