// `--json` on the commands that print statistics (stdout is one JSON object with the expected
// keys), `globalvis bench` (checks, hashes, budget, the docs section) and progress output only on
// a terminal.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>
#include <vector>

#include "quake/prt_file.h"
#include "quake/prt_portal_graph.h"
#include "radiosity/hierarchical_radiosity.h"
#include "support/run_cli.h"
#include "support/temp_dir.h"
#include "util/peak_memory.h"
#include "visibility/cell_pvs.h"

namespace gv {
namespace {

using nlohmann::json;
using test::quoted;

/// Runs `globalvis ARGS`, expects exit code `code`, returns stdout parsed (fails on non-JSON).
json runJson(const std::string& args, int code = 0) {
  const test::CliResult r = test::runCliStdout(args);
  EXPECT_EQ(r.exitCode, code) << args << "\n" << r.output;
  json j = json::parse(r.output, nullptr, false);
  EXPECT_FALSE(j.is_discarded()) << "not JSON: " << r.output;
  EXPECT_TRUE(j.is_object()) << r.output;
  return j;
}

void expectKeys(const json& j, std::initializer_list<const char*> keys) {
  for (const char* k : keys)
    EXPECT_TRUE(j.contains(k)) << "missing key " << k << " in " << j.dump();
}

const std::string kQuakeDir = std::string(GV_SHARED_DATA_DIR) + "/quake/";

class JsonCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratchDir();
    obj_ = dir_ / "c.obj";
    ASSERT_EQ(test::runCli("gen cornell -o " + quoted(obj_)).exitCode, 0);
  }
  std::filesystem::path dir_, obj_;
};

TEST_F(JsonCliTest, CellsVisVerifyPrintOneObject) {
  const json cells = runJson("cells " + quoted(obj_) + " -o " + quoted(dir_ / "cells") + " --json");
  expectKeys(cells, {"scene", "patches", "leaf_cells", "portals", "bsp_seconds", "portal_seconds"});
  EXPECT_EQ(cells["patches"], 19);
  // The same figures as the stats.json it writes.
  const json written = json::parse(test::readFile(dir_ / "cells" / "stats.json"));
  EXPECT_EQ(cells["leaf_cells"], written["leaf_cells"]);

  const json vis = runJson("vis " + quoted(obj_) + " -o " + quoted(dir_ / "vis") + " --json");
  expectKeys(vis, {"scene", "subdivision", "visibility"});

  const json verify =
      runJson("verify " + quoted(dir_ / "vis") + " --rays 3000 --segments 500 --json");
  expectKeys(verify, {"rays", "missing_pairs", "segments", "blocked_visible", "missing_blockers",
                      "ok", "examples"});
  EXPECT_EQ(verify["rays"], 3000);
  EXPECT_EQ(verify["ok"], true);
}

TEST_F(JsonCliTest, RadiosityPrintsItsStats) {
  const json r = runJson("radiosity " + quoted(obj_) + " -o " + quoted(dir_ / "rad") +
                         " --no-pictures --max-refinements 1 --rays 4 --json");
  expectKeys(r, {"scene", "output"});
  const json written = json::parse(test::readFile(dir_ / "rad" / "stats.json"));
  for (const auto& [key, value] : written.items()) EXPECT_EQ(r[key], value) << key;
}

// --quality sets the solver's settings and stats.json says which, with the run's time and
// memory; a bad level or a level with --epsilon is refused.
TEST_F(JsonCliTest, RadiosityQualityAndRunFigures) {
  const json draft = runJson("radiosity " + quoted(obj_) + " -o " + quoted(dir_ / "d") +
                             " --no-pictures --quality draft --json");
  EXPECT_EQ(draft["options"]["quality"], "draft");
  EXPECT_EQ(draft["options"]["epsilon"], 1e-3);
  EXPECT_EQ(draft["options"]["relative_epsilon"], 0.1);
  // The link budget by default: from this machine's memory, never below the library's 20 M.
  EXPECT_EQ(draft["options"]["max_links"].get<size_t>(), linkBudgetForMemory(usableMemoryBytes()));
  EXPECT_GE(draft["options"]["max_links"].get<size_t>(), RadiosityOptions{}.maxLinks);
  const json& run = draft["run"];
  expectKeys(run, {"load_seconds", "visibility_seconds", "solve_seconds", "write_seconds",
                   "picture_seconds", "total_seconds", "peak_resident_bytes"});
  EXPECT_GT(run["peak_resident_bytes"].get<double>(), 1e6);
  EXPECT_GE(run["total_seconds"].get<double>(), run["solve_seconds"].get<double>());
  const json custom = runJson("radiosity " + quoted(obj_) + " -o " + quoted(dir_ / "c") +
                              " --no-pictures --epsilon 0.0005 --relative-epsilon 0.03 --json");
  EXPECT_EQ(custom["options"]["quality"], "custom");
  EXPECT_EQ(custom["options"]["epsilon"], 0.0005);
  EXPECT_EQ(custom["options"]["relative_epsilon"], 0.03);
  EXPECT_EQ(
      runJson("radiosity " + quoted(obj_) + " -o " + quoted(dir_ / "m") +
              " --no-pictures --quality draft --max-links 123456 --json")["options"]["max_links"],
      123456);
  EXPECT_EQ(
      runJson("radiosity " + quoted(obj_) + " -o " + quoted(dir_ / "m") +
              " --no-pictures --quality draft --max-links auto --json")["options"]["max_links"],
      draft["options"]["max_links"]);
  // A finer level makes more links.
  EXPECT_GT(custom["totals"]["links"].get<size_t>(), draft["totals"]["links"].get<size_t>());
  EXPECT_NE(
      test::runCli("radiosity " + quoted(obj_) + " -o " + quoted(dir_ / "x") + " --quality best")
          .exitCode,
      0);
  EXPECT_NE(test::runCli("radiosity " + quoted(obj_) + " -o " + quoted(dir_ / "x") +
                         " --quality low --epsilon 1e-3")
                .exitCode,
            0);
}

TEST(JsonCli, PvsStatsMatchTheWrittenRows) {
  const auto dir = test::scratchDir();
  const json j = runJson("pvs " + quoted(std::filesystem::path(kQuakeDir + "qbspfeatures.prt")) +
                         " -o " + quoted(dir / "pvs.txt") + " --json");
  expectKeys(j,
             {"leafs", "clusters", "portals", "mean_leafs_visible", "stabbing_tests", "seconds"});
  // Independently of the JSON: the rows written, one per leaf, `L n v1 ... vn`, each the row
  // the library's PVS expanded leaf by leaf gives (the file is written per cluster: its 157
  // leafs fall in 18 clusters).
  const PrtFile prt = readPrtFile(kQuakeDir + "qbspfeatures.prt");
  const LeafPvs expected = expandToLeafs(prt, computeCellPvs(portalGraphOf(prt)).visibleCells);
  std::ifstream in(dir / "pvs.txt");
  size_t rows = 0, total = 0;
  for (std::string line; std::getline(in, line); ++rows) {
    std::istringstream ls(line);
    size_t leaf = 0, n = 0;
    ls >> leaf >> n;
    EXPECT_EQ(leaf, rows);
    std::vector<uint32_t> row(n);
    for (uint32_t& v : row) ls >> v;
    EXPECT_TRUE(ls && (ls >> std::ws).eof()) << line;
    ASSERT_LT(leaf, expected.visibleLeafs.size());
    EXPECT_EQ(row, expected.visibleLeafs[leaf]) << "leaf " << leaf;
    total += n;
  }
  EXPECT_EQ(j["leafs"], rows);
  EXPECT_EQ(j["leafs"], 157);  // the header of qbspfeatures.prt
  EXPECT_NEAR(j["mean_leafs_visible"].get<double>(), double(total) / double(rows), 1e-9);
}

TEST(BenchCli, SmallOfficeIsCheckedAndHashedTheSameTwice) {
  const std::string args = "bench --no-maps --no-levels --office-patches 150 --json";
  const json a = runJson(args), b = runJson(args);
  expectKeys(a, {"machine", "date", "ok", "scenes"});
  EXPECT_EQ(a["ok"], true);
  ASSERT_EQ(a["scenes"].size(), 1u);
  const json& s = a["scenes"][0];
  expectKeys(s, {"scene", "patches", "seconds", "cells", "portals", "pairs_listed", "pairs_visible",
                 "pairs_partial", "mean_blockers_per_partial", "visibility_hash", "checks_passed",
                 "failures", "notes"});
  EXPECT_EQ(s["pairs_listed"].get<uint64_t>(),
            s["pairs_visible"].get<uint64_t>() + s["pairs_partial"].get<uint64_t>());
  const auto checks = s["checks_passed"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(checks.begin(), checks.end(), "cells"), checks.end());
  EXPECT_NE(std::find(checks.begin(), checks.end(), "verify 4000 rays"), checks.end());
  EXPECT_EQ(s["visibility_hash"].get<std::string>().size(), 16u);
  EXPECT_EQ(s["visibility_hash"], b["scenes"][0]["visibility_hash"]);
}

TEST(BenchCli, MapRowHasItsPvs) {
  const auto dir = test::scratchDir();
  std::filesystem::copy_file(kQuakeDir + "qbspfeatures.map", dir / "qbspfeatures.map");
  std::filesystem::copy_file(kQuakeDir + "qbspfeatures.prt", dir / "qbspfeatures.prt");
  const json j =
      runJson("bench --no-offices --no-levels --all-maps --maps " + quoted(dir) + " --json");
  ASSERT_EQ(j["scenes"].size(), 1u);
  const json& s = j["scenes"][0];
  EXPECT_EQ(s["scene"], "qbspfeatures");
  EXPECT_EQ(s["pvs_leafs"], 157);
  EXPECT_EQ(s["pvs_hash"].get<std::string>().size(), 16u);
  EXPECT_EQ(j["ok"], true);
}

TEST(BenchCli, ABadMapFailsItsRowAndTheExitCode) {
  const auto dir = test::scratchDir();
  test::writeFile(dir / "broken.map", "{\n\"classname\" \"worldspawn\"\n{\n( 0 0 0 ) ( 1 0 0 )\n");
  std::filesystem::copy_file(kQuakeDir + "qbspfeatures.prt", dir / "broken.prt");
  const json j =
      runJson("bench --no-offices --no-levels --all-maps --maps " + quoted(dir) + " --json", 1);
  EXPECT_EQ(j["ok"], false);
  ASSERT_EQ(j["scenes"].size(), 1u);
  const json& s = j["scenes"][0];
  EXPECT_EQ(s["ok"], false);
  ASSERT_FALSE(s["failures"].empty());
  // The importer's message names the file and line.
  EXPECT_NE(s["failures"][0].get<std::string>().find("broken.map:"), std::string::npos)
      << s["failures"];
  // Text mode says so too.
  const auto text = test::runCli("bench --no-offices --no-levels --all-maps --maps " + quoted(dir));
  EXPECT_EQ(text.exitCode, 1);
  EXPECT_NE(text.output.find("FAILED"), std::string::npos) << text.output;
}

TEST(BenchCli, LevelRowHasItsLitVariantsRadiosityAgainstPhotons) {
  // A directory laid out as ../shared/data/levels: a level and its lit- variant (here the
  // Cornell box for both: small, and lit either way).
  const auto dir = test::scratchDir();
  ASSERT_EQ(test::runCli("gen cornell -o " + quoted(dir / "box.obj")).exitCode, 0);
  std::filesystem::copy_file(dir / "box.obj", dir / "lit-box.obj");
  const json j = runJson("bench --no-offices --no-maps --levels " + quoted(dir) +
                         " --radiosity --photons 300000 --json");
  EXPECT_EQ(j["ok"], true) << j.dump(1);
  ASSERT_EQ(j["scenes"].size(), 1u);  // the lit variant joins its level's row
  const json& s = j["scenes"][0];
  EXPECT_EQ(s["scene"], "box");
  EXPECT_EQ(s["kind"], "level");
  EXPECT_FALSE(s["pairs_listed"].is_null());
  ASSERT_FALSE(s["excess"].is_null());
  EXPECT_GE(s["excess"].get<double>(), 0.0);
  EXPECT_LE(s["excess"].get<double>(), 0.5);  // a box: nearly every listed pair sees
  ASSERT_FALSE(s["photon_l2_reflected"].is_null());
  EXPECT_LT(s["photon_l2_reflected"].get<double>(), 0.05);  // issue #18's level target
  EXPECT_EQ(s["photon_leak_surfaces"], 0);
  EXPECT_FALSE(s["seconds"]["photons"].is_null());
  const auto checks = s["checks_passed"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(checks.begin(), checks.end(), "no leak against 300000 photons"), checks.end())
      << s["checks_passed"];
  // Without --radiosity: the level's visibility only.
  const json v = runJson("bench --no-offices --no-maps --levels " + quoted(dir) + " --json");
  EXPECT_TRUE(v["scenes"][0]["photon_l2_reflected"].is_null());
  // A directory that is not there, named: an input error, not an empty table.
  EXPECT_NE(test::runCli("bench --no-offices --no-maps --levels " + quoted(dir / "nope")).exitCode,
            0);
}

TEST(BenchCli, BudgetSkipsStagesAndSaysSo) {
  const json j =
      runJson("bench --no-maps --no-levels --office-patches 150 --max-seconds 1e-9 --json");
  const json& s = j["scenes"][0];
  EXPECT_TRUE(s["seconds"]["visibility"].is_null());
  ASSERT_FALSE(s["notes"].empty());
  EXPECT_NE(s["notes"][0].get<std::string>().find("budget"), std::string::npos) << s["notes"];
  EXPECT_EQ(j["ok"], true);  // skipped is not failed
}

TEST(BenchCli, UpdateDocsRewritesOnlyItsSection) {
  const auto dir = test::scratchDir();
  const auto md = dir / "BENCH.md";
  test::writeFile(md, "# Benchmarks\n\nHand-written text.\n");
  const std::string args =
      "bench --no-maps --no-levels --office-patches 150 --update-docs " + quoted(md);
  ASSERT_EQ(test::runCli(args).exitCode, 0);
  ASSERT_EQ(test::runCli(args).exitCode, 0);
  const std::string text = test::readFile(md);
  EXPECT_EQ(text.rfind("# Benchmarks\n\nHand-written text.\n", 0), 0u) << text;
  auto occurrences = [&](const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(occurrences("<!-- bench:begin -->"), 1u) << text;
  EXPECT_EQ(occurrences("<!-- bench:end -->"), 1u) << text;
  EXPECT_EQ(occurrences("| office 1x1x3 |"), 1u) << text;
  EXPECT_NE(text.find("hardware threads"), std::string::npos) << text;
}

TEST(ProgressOutput, NoneWhenStderrIsNotATerminal) {
  const auto dir = test::scratchDir();
  const auto obj = dir / "o.obj";
  ASSERT_EQ(test::runCli("gen office -o " + quoted(obj)).exitCode, 0);
  // runCli sends stderr into a pipe: not a terminal.
  const auto vis = test::runCli("vis " + quoted(obj) + " -o " + quoted(dir / "vis"));
  ASSERT_EQ(vis.exitCode, 0) << vis.output;
  EXPECT_EQ(vis.output.find('\r'), std::string::npos) << vis.output;
  EXPECT_EQ(vis.output.find("visibility (per source patch) ["), std::string::npos) << vis.output;
  EXPECT_EQ(vis.output.find("BSP ["), std::string::npos) << vis.output;
  const auto cells = test::runCli("cells " + quoted(obj) + " -o " + quoted(dir / "cells"));
  EXPECT_EQ(cells.output.find('\r'), std::string::npos) << cells.output;
  const auto pvs =
      test::runCli("pvs " + quoted(std::filesystem::path(kQuakeDir + "qbspfeatures.prt")) + " -o " +
                   quoted(dir / "pvs.txt"));
  EXPECT_EQ(pvs.output.find('\r'), std::string::npos) << pvs.output;
}

TEST(ProgressOutput, ABarOnATerminal) {
  if (test::runShell("command -v script > /dev/null").exitCode != 0)
    GTEST_SKIP() << "util-linux `script` (a pseudo-terminal) is not installed";
  const auto dir = test::scratchDir();
  const auto obj = dir / "o.obj";
  ASSERT_EQ(test::runCli("gen office -o " + quoted(obj)).exitCode, 0);
  // `script` runs the command on a pseudo-terminal: stderr is a terminal there. No first-draw
  // delay, so that the bars show however fast the machine is.
  const std::string command = std::string("GLOBALVIS_PROGRESS_DELAY=0 '") + GV_CLI_PATH + "' vis " +
                              quoted(obj) + " -o " + quoted(dir / "vis") +
                              " --threads 1 > /dev/null";
  const auto r = test::runShell("script -qec \"" + command + "\" /dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find('\r'), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("visibility (per source patch) ["), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("100.0 %"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace gv
