// `globalvis cells SCENE -o DIR` end to end: files written, groups per cell and portal, the §7.1
// figures in stats.json, a cells.prt that `globalvis pvs` reads, bad input → exit 2.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/run_cli.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

size_t countLines(const std::string& text, const std::string& prefix) {
  size_t n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

TEST(SubdivisionCli, WritesCellsPortalsAndStats) {
  const auto dir = test::scratchDir();
  const std::string obj = (dir / "office.obj").string();
  auto r = test::runCli("gen office -o '" + obj + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = test::runCli("cells '" + obj + "' -o '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto stats = nlohmann::json::parse(test::readFile(dir / "out" / "stats.json"));
  const size_t cells = stats.at("leaf_cells").get<size_t>();
  const size_t portals = stats.at("portals").get<size_t>();
  EXPECT_GT(cells, 100u);
  EXPECT_GT(portals, 100u);
  EXPECT_GT(stats.at("mean_boundary_faces_per_cell").get<double>(), 4.0);
  EXPECT_GT(stats.at("mean_coaffine_patches_per_cell").get<double>(), 0.0);
  EXPECT_GE(stats.at("bsp_seconds").get<double>(), 0.0);
  EXPECT_GE(stats.at("portal_seconds").get<double>(), 0.0);
  EXPECT_EQ(countLines(test::readFile(dir / "out" / "cells.obj"), "g cell_"), cells);
  const std::string portalObj = test::readFile(dir / "out" / "portals.obj");
  EXPECT_EQ(countLines(portalObj, "g portal_"), portals);
  EXPECT_EQ(countLines(portalObj, "f "), portals);
  // cells.prt: the same graph for `globalvis pvs` (its orientation: portal_file_test.cpp).
  r = test::runCliStdout("pvs '" + (dir / "out" / "cells.prt").string() + "' -o '" +
                         (dir / "pvs.txt").string() + "' --json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto pvs = nlohmann::json::parse(r.output);
  EXPECT_EQ(pvs.at("leafs").get<size_t>(), cells);
  EXPECT_EQ(pvs.at("portals").get<size_t>(), portals);
  // Sealed offices: no cell sees them all, every cell sees itself and a neighbour at least.
  const double mean = pvs.at("mean_leafs_visible").get<double>();
  EXPECT_GT(mean, 1.0);
  EXPECT_LT(mean, 0.5 * double(cells));
}

TEST(SubdivisionCli, MissingSceneIsBadInput) {
  const auto dir = test::scratchDir();
  const auto r = test::runCli("cells /nonexistent/x.obj -o '" + (dir / "out").string() + "'");
  EXPECT_EQ(r.exitCode, 2) << r.output;
}

}  // namespace
}  // namespace gv
