// Issue #18's targets on whole lit real levels, the way a user runs them: `globalvis radiosity`
// on a level of the shared set, then `globalvis photons --compare` (an independent light tracer:
// no form factors, no mesh, no visibility graph). The bounds are the issue's, not today's error:
// area-weighted L2 of B−Ke ≤ 5 %, no leak (a channel lit where ≥ 10 photon hits were expected
// and none came), no 3-unit region off by more than 15 %; and every channel is accounted for.
// 4 M photons keep the test short: fewer channels can be judged than with the 32 M of the
// benchmark (docs/BENCHMARKS.md), and the counts of what was left out are checked too.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/run_cli.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

using nlohmann::json;
using test::quoted;

void expectMatchesLightTracing(const std::string& level, const std::string& mode) {
  const std::filesystem::path path =
      std::filesystem::path(GV_SHARED_DATA_DIR) / "levels" / (level + ".obj");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const std::filesystem::path dir = test::scratchDir();
  const test::CliResult solved =
      test::runCli("radiosity " + quoted(path) + " -o " + quoted(dir / "r") +
                   " --no-pictures --visibility " + mode);
  ASSERT_EQ(solved.exitCode, 0) << solved.output;
  // Exit code 1 means channels beyond 4 standard errors + 1 %: judged below by the issue's
  // measures instead (per-channel noise at 4 M photons is not the target).
  const test::CliResult compared =
      test::runCliStdout("photons " + quoted(path) + " -o " + quoted(dir / "p") +
                         " --photons 4000000 --json --compare " + quoted(dir / "r"));
  ASSERT_TRUE(compared.exitCode == 0 || compared.exitCode == 1) << compared.output;
  const json j = json::parse(compared.output, nullptr, false);
  ASSERT_TRUE(j.is_object()) << compared.output;
  const json& c = j["comparison"];
  const double l2 = c["l2_reflected"].get<double>();
  const double worst = c["regions"]["worst"]["relative"].get<double>();
  const json& ch = c["channels"];
  std::printf(
      "%s %s: L2 %.4f, leaks %d, worst region %+.4f (%d compared), channels %d: %d "
      "compared, %d noisy, %d without a photon (%d too dim, %d unlit)\n",
      level.c_str(), mode.c_str(), l2, ch["leak"].get<int>(), worst,
      c["regions"]["compared"].get<int>(), ch["total"].get<int>(), ch["compared"].get<int>(),
      ch["noisy"].get<int>(), ch["zero_photon"].get<int>(), ch["too_dim"].get<int>(),
      ch["unlit"].get<int>());
  ::testing::Test::RecordProperty("l2_reflected", std::to_string(l2));
  ::testing::Test::RecordProperty("worst_region", std::to_string(worst));
  EXPECT_LE(l2, 0.05);
  EXPECT_EQ(c["leaks"]["patches"].get<int>(), 0) << c["leaks"].dump();
  EXPECT_LE(std::abs(worst), 0.15) << c["regions"]["worst"].dump();
  // The comparison is not vacuous, and nothing is silently left out.
  EXPECT_GT(c["regions"]["compared"].get<int>(), 100);
  EXPECT_GT(ch["compared"].get<int>(), 100);
  EXPECT_EQ(ch["total"].get<int>(), 3 * c["surfaces"].get<int>());
  EXPECT_EQ(ch["compared"].get<int>() + ch["noisy"].get<int>() + ch["zero_photon"].get<int>(),
            ch["total"].get<int>());
  EXPECT_EQ(ch["leak"].get<int>() + ch["too_dim"].get<int>() + ch["unlit"].get<int>(),
            ch["zero_photon"].get<int>());
}

// An arena level (Quake 3 brush soup: coincident faces, overlapping brushes, closed thin
// solids), in the mode that carries light along the visibility graph's blocker lists.
TEST(LitLevelCliTest, ArenaLevelInBlockersModeMatchesLightTracing) {
  expectMatchesLightTracing("lit-q3-dm4ish", "blockers");
}

// A 2.5D sector level (sector light levels as emitters), in the default `rays` mode.
TEST(LitLevelCliTest, SectorLevelInRaysModeMatchesLightTracing) {
  expectMatchesLightTracing("lit-doom-fd2-map01", "rays");
}

}  // namespace
}  // namespace gv
