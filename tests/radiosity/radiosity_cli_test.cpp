// `globalvis radiosity` end to end: an emitter over a receiver through OBJ/MTL files, checked
// against ρ E F with F from Howell's catalogue (C-11), and the output contract of DESIGN.md.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

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
