// `globalvis photons`: the light-tracing reference through the CLI (Howell C-11 through OBJ/MTL
// files), its comparison of a `radiosity` run, and its errors on bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "report/run_files.h"
#include "support/howell_pair.h"
#include "support/run_cli.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

TEST(PhotonsCliTest, ReferenceMatchesHowellAndComparesARun) {
  const auto dir = test::scratchDir();
  const auto scene = test::writeHowellPair(dir);
  const auto run = dir / "run", ref = dir / "ref";
  ASSERT_EQ(
      test::runCli("radiosity '" + scene.string() + "' -o '" + run.string() + "' -q --no-pictures")
          .exitCode,
      0);
  const test::CliResult r =
      test::runCli("photons '" + scene.string() + "' -o '" + ref.string() +
                   "' --photons 400000 --compare '" + run.string() + "' --allowance 0.02");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("vs photons over"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("L2 of B-Ke over all 2 patches"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("leaks: 0 patches"), std::string::npos) << r.output;

  // Both files have radiosity.txt's format, so the report module's reader takes them.
  const std::vector<Rgb> b = readRadiosityTxt((ref / "radiosity.txt").string(), 2);
  const std::vector<Rgb> e = readRadiosityTxt((ref / "standard_error.txt").string(), 2);
  const double expected = 0.6 * 3 * test::kHowellC11;  // ρ E F, F from Howell C-11 (X = Y = 1)
  EXPECT_NEAR(b[0].r, expected, 4 * e[0].r);
  EXPECT_LT(e[0].r, 0.01 * expected);
  EXPECT_EQ(b[1].r, 3);  // the emitter reflects nothing: B = E exactly
  std::ifstream stats(ref / "stats.json");
  const nlohmann::json j = nlohmann::json::parse(stats);
  EXPECT_EQ(j["photons"], 400000);
  EXPECT_EQ(j["comparison"]["beyond_tolerance"], 0);
  EXPECT_LT(j["comparison"]["max_relative"].get<double>(), 0.02);
  // Every channel counted: the receiver's three compared, the emitter's (ρ = 0) unlit.
  const nlohmann::json& n = j["comparison"]["channels"];
  EXPECT_EQ(n["total"], 6);
  EXPECT_EQ(n["compared"], 3);
  EXPECT_EQ(n["zero_photon"], 3);
  EXPECT_EQ(n["unlit"], 3);
  EXPECT_EQ(j["comparison"]["leaks"]["channels"], 0);
  EXPECT_LT(j["comparison"]["l2_reflected"].get<double>(), 0.02);
  EXPECT_EQ(j["comparison"]["regions"]["size"], 3.0);
  EXPECT_LT(std::abs(j["comparison"]["regions"]["worst"]["relative"].get<double>()), 0.02);
}

// --reference compares a run against an earlier reference without shooting again: the same
// figures as comparing in the run that shot the photons, leaks included (photon_power kept).
TEST(PhotonsCliTest, AStoredReferenceComparesAsTheOriginal) {
  const auto dir = test::scratchDir();
  const auto scene = test::writeHowellPair(dir);
  std::filesystem::create_directories(dir / "bright");
  test::writeFile(
      dir / "bright" / "radiosity.txt",
      "# made up\n0 " + std::to_string(1.1 * 0.6 * 3 * test::kHowellC11) + " 0.1 0.1\n1 3 2 1\n");
  const std::string compare = " --compare '" + (dir / "bright").string() + "' --json";
  const test::CliResult shot =
      test::runCliStdout("photons '" + scene.string() + "' -o '" + (dir / "ref").string() +
                         "' --photons 100000" + compare);
  const test::CliResult reused = test::runCliStdout(
      "photons '" + scene.string() + "' --reference '" + (dir / "ref").string() + "'" + compare);
  EXPECT_EQ(shot.exitCode, 1) << shot.output;
  EXPECT_EQ(reused.exitCode, 1) << reused.output;
  const nlohmann::json a = nlohmann::json::parse(shot.output, nullptr, false);
  const nlohmann::json b = nlohmann::json::parse(reused.output, nullptr, false);
  ASSERT_TRUE(a.is_object() && b.is_object()) << shot.output << reused.output;
  // radiosity.txt keeps 9 significant digits: counts agree exactly, errors to ~1e-8.
  const nlohmann::json &ca = a["comparison"], &cb = b["comparison"];
  for (const char* key : {"channels", "leaks", "beyond_tolerance", "compared", "worst_patch"})
    EXPECT_EQ(ca[key].dump(), cb[key].dump()) << key;
  for (const char* key : {"l2_reflected", "max_relative", "rms_relative", "mean_signed"})
    EXPECT_NEAR(ca[key].get<double>(), cb[key].get<double>(), 1e-8) << key;
  EXPECT_EQ(b["reference"], (dir / "ref").string());

  // Without --compare, or from a directory that is not a photons output, it says why.
  const test::CliResult alone =
      test::runCli("photons '" + scene.string() + "' --reference '" + (dir / "ref").string() + "'");
  EXPECT_EQ(alone.exitCode, 2) << alone.output;
  EXPECT_NE(alone.output.find("--compare"), std::string::npos) << alone.output;
  const test::CliResult notPhotons = test::runCli("photons '" + scene.string() + "' --reference '" +
                                                  (dir / "bright").string() + "'" + compare);
  EXPECT_EQ(notPhotons.exitCode, 2) << notPhotons.output;
  EXPECT_NE(notPhotons.output.find("standard_error.txt"), std::string::npos) << notPhotons.output;
}

TEST(PhotonsCliTest, LeakExitsOneAndIsNamed) {
  const auto dir = test::scratchDir();
  test::writeHowellPair(dir);
  // The pair and a third square below the receiver facing down, which no photon can reach.
  test::writeFile(dir / "leak.obj",
                  "mtllib pair.mtl\n"
                  "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                  "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                  "v 0 0 -1\nv 1 0 -1\nv 1 1 -1\nv 0 1 -1\n"
                  "usemtl grey\nf 1 2 3 4\n"
                  "usemtl light\nf 5 8 7 6\n"
                  "usemtl grey\nf 9 12 11 10\n");
  // A "run" right on the receiver that lights the third square: (0.1 / 0.6) · 1 m² against
  // photons of 3 / 100000 in red: ~5600 hits expected.
  std::filesystem::create_directories(dir / "leaky");
  const std::string receiver = std::to_string(0.6 * 3 * test::kHowellC11) + " " +
                               std::to_string(0.6 * 2 * test::kHowellC11) + " " +
                               std::to_string(0.6 * 1 * test::kHowellC11);
  test::writeFile(dir / "leaky" / "radiosity.txt",
                  "# made up\n0 " + receiver + "\n1 3 2 1\n2 0.1 0 0\n");
  const test::CliResult r = test::runCli(
      "photons '" + (dir / "leak.obj").string() + "' -o '" + (dir / "ref").string() +
      "' --photons 100000 --allowance 0.05 --compare '" + (dir / "leaky").string() + "'");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("leaks: 1 patches"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("patch 2 channel 0"), std::string::npos) << r.output;
  std::ifstream stats(dir / "ref" / "stats.json");
  const nlohmann::json j = nlohmann::json::parse(stats);
  EXPECT_EQ(j["comparison"]["beyond_tolerance"], 0);
  EXPECT_EQ(j["comparison"]["leaks"]["channels"], 1);
  EXPECT_EQ(j["comparison"]["channels"]["unlit"], 5);  // the emitter's 3, the square's g and b
  EXPECT_NEAR(j["comparison"]["leaks"]["worst"][0]["expected_hits"].get<double>(),
              0.1 / 0.6 * 100000 / 3, 1);
}

TEST(PhotonsCliTest, ComparisonBeyondToleranceExitsOne) {
  const auto dir = test::scratchDir();
  const auto scene = test::writeHowellPair(dir);
  // A "run" that is 10 % too bright on the receiver.
  std::filesystem::create_directories(dir / "bright");
  test::writeFile(
      dir / "bright" / "radiosity.txt",
      "# made up\n0 " + std::to_string(1.1 * 0.6 * 3 * test::kHowellC11) + " 0.1 0.1\n1 3 2 1\n");
  const test::CliResult r =
      test::runCli("photons '" + scene.string() + "' -o '" + (dir / "ref").string() +
                   "' --photons 100000 --compare '" + (dir / "bright").string() + "'");
  EXPECT_EQ(r.exitCode, 1) << r.output;
}

TEST(PhotonsCliTest, BadInputIsNamed) {
  const auto dir = test::scratchDir();
  const auto scene = test::writeHowellPair(dir);
  const test::CliResult missing = test::runCli("photons '" + (dir / "nope.obj").string() +
                                               "' -o '" + (dir / "o").string() + "'");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find("nope.obj"), std::string::npos) << missing.output;
  // A run of another scene: its radiosity.txt has the wrong number of patches.
  std::filesystem::create_directories(dir / "other");
  test::writeFile(dir / "other" / "radiosity.txt", "0 1 1 1\n");
  const test::CliResult wrong =
      test::runCli("photons '" + scene.string() + "' -o '" + (dir / "o").string() +
                   "' --compare '" + (dir / "other").string() + "'");
  EXPECT_EQ(wrong.exitCode, 2) << wrong.output;
  EXPECT_NE(wrong.output.find("radiosity.txt"), std::string::npos) << wrong.output;
  EXPECT_NE(
      test::runCli("photons '" + scene.string() + "' -o '" + (dir / "o").string() + "' --photons 0")
          .exitCode,
      0);
  EXPECT_NE(
      test::runCli("photons '" + scene.string() + "' -o '" + (dir / "o").string() + "' --batches 1")
          .exitCode,
      0);
}

}  // namespace
}  // namespace gv
