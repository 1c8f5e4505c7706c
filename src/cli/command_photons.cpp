// `globalvis photons SCENE -o DIR`: the independent light-tracing reference (photon_reference.h)
// with per-patch standard errors, and optionally a radiosity run compared against it.
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/output_files.h"
#include "cli/scene_input.h"
#include "radiosity/photon_comparison.h"
#include "radiosity/photon_reference.h"
#include "radiosity/radiosity_io.h"
#include "raycast/embree_scene.h"
#include "report/run_files.h"
#include "scene/scene_io.h"
#include "util/input_error.h"
#include "util/timing.h"

namespace gv::cli {
namespace {

nlohmann::json channelsJson(const PhotonChannelCounts& n) {
  return {{"total", n.total},
          {"compared", n.compared},
          {"noisy", n.noisy},
          {"noisy_rule", fmt::format("photon relative standard error above {:g} %",
                                     100 * kMeaningfulPhotonNoise)},
          {"zero_photon", n.zeroPhoton},
          {"leak", n.leaks},
          {"too_dim", n.tooDim},
          {"unlit", n.unlit}};
}

nlohmann::json leaksJson(const PhotonComparison& c) {
  nlohmann::json worst = nlohmann::json::array();
  for (const PhotonLeak& l : c.worstLeaks)
    worst.push_back({{"patch", l.patch},
                     {"channel", l.channel},
                     {"expected_hits", l.expectedHits},
                     {"solver_reflected", l.solver}});
  return {{"channels", c.channels.leaks},
          {"surfaces", c.leakSurfaces},
          {"patches", c.leakPatches},
          {"power_share", c.leakedPowerShare},
          {"min_expected_hits", kLeakExpectedHits},
          {"worst", worst}};
}

nlohmann::json regionsJson(const PhotonComparison& c) {
  nlohmann::json j = {{"size", c.regionSize},          {"channels", c.regionChannels},
                      {"compared", c.regionsCompared}, {"noisy", c.regionsNoisy},
                      {"small", c.regionsSmall},       {"max_noise", kMeaningfulRegionNoise},
                      {"min_share", kMinRegionShare}};
  if (c.worstRegion) {
    const PhotonRegion& w = *c.worstRegion;
    j["worst"] = {{"low", {w.low.x, w.low.y, w.low.z}},
                  {"channel", w.channel},
                  {"relative", w.relative},
                  {"solver", w.solver},
                  {"photons", w.photons},
                  {"patches", w.patches}};
  }
  return j;
}

/// The text lines of the counts, leaks and regions (from the stats' JSON, as printed above).
void printCounts(const nlohmann::json& c) {
  const auto& n = c["channels"];
  fmt::print(
      "L2 of B-Ke over all {} patches and channels: {:.2f} % (the photons' own noise alone: about "
      "{:.2f} %; {} surfaces, {} coincident twin groups of {} patches)\n",
      c["surfaces"].get<size_t>() - c["twin_groups"].get<size_t>() +
          c["twin_patches"].get<size_t>(),
      c["l2_reflected"].is_number() ? 100 * c["l2_reflected"].get<double>() : INFINITY,
      c["l2_photon_noise"].is_number() ? 100 * c["l2_photon_noise"].get<double>() : INFINITY,
      c["surfaces"].get<size_t>(), c["twin_groups"].get<size_t>(), c["twin_patches"].get<size_t>());
  fmt::print(
      "channels: {} = {} compared + {} left out as noisy ({}) + {} without a photon ({} leaks, {} "
      "too dim to tell: < {:g} hits expected, {} unlit in the solution too)\n",
      n["total"].get<size_t>(), n["compared"].get<size_t>(), n["noisy"].get<size_t>(),
      n["noisy_rule"].get<std::string>(), n["zero_photon"].get<size_t>(), n["leak"].get<size_t>(),
      n["too_dim"].get<size_t>(), kLeakExpectedHits, n["unlit"].get<size_t>());
  const auto& l = c["leaks"];
  fmt::print("leaks: {} patches ({} surfaces), {:.3f} % of the solution's reflected power\n",
             l["patches"].get<size_t>(), l["surfaces"].get<size_t>(),
             100 * l["power_share"].get<double>());
  for (const auto& w : l["worst"])
    fmt::print("  patch {} channel {}: {:.0f} photon hits expected, solver B-Ke {:.4g}\n",
               w["patch"].get<size_t>(), w["channel"].get<int>(), w["expected_hits"].get<double>(),
               w["solver_reflected"].get<double>());
  const auto& r = c["regions"];
  fmt::print(
      "regions ({:g}-unit cubes): {} region channels, {} compared, {} left out as noisy "
      "(photon relative standard error above {:g} % or no photon), {} below {:g} % of "
      "the reflected power\n",
      r["size"].get<double>(), r["channels"].get<size_t>(), r["compared"].get<size_t>(),
      r["noisy"].get<size_t>(), 100 * kMeaningfulRegionNoise, r["small"].get<size_t>(),
      100 * kMinRegionShare);
  if (r.contains("worst")) {
    const auto& w = r["worst"];
    const auto& low = w["low"];
    fmt::print(
        "worst region: {:+.2f} % (channel {}, cube from ({:g}, {:g}, {:g}), {} patches, solver "
        "{:.4g} vs photons {:.4g})\n",
        100 * w["relative"].get<double>(), w["channel"].get<int>(), low[0].get<double>(),
        low[1].get<double>(), low[2].get<double>(), w["patches"].get<size_t>(),
        w["solver"].get<double>(), w["photons"].get<double>());
  }
}

/// An earlier `photons` output directory as a PhotonResult: radiosity.txt, standard_error.txt
/// and the photon count and per-photon power of its stats.json. Throws InputError naming the
/// file when one is missing or was written for another patch count.
PhotonResult readPhotonReference(const std::filesystem::path& dir, size_t patchCount) {
  PhotonResult ref;
  ref.radiosity = readRadiosityTxt((dir / "radiosity.txt").string(), patchCount);
  ref.standardError = readRadiosityTxt((dir / "standard_error.txt").string(), patchCount);
  const std::filesystem::path statsPath = dir / "stats.json";
  const nlohmann::json stats = *readStatsJson(statsPath);
  if (!stats.contains("photon_power") || !stats.contains("photons"))
    throw InputError(statsPath.string(), 0,
                     "no photons or photon_power: not a `globalvis photons` directory, or one "
                     "written before photon_power was recorded (run photons again)");
  try {
    ref.photons = stats["photons"].get<uint64_t>();
    ref.rays = stats.value("rays", uint64_t{0});
    const auto& power = stats["photon_power"];
    ref.photonPower = {power.at(0).get<double>(), power.at(1).get<double>(),
                       power.at(2).get<double>()};
  } catch (const nlohmann::json::exception& e) {
    throw InputError(statsPath.string(), 0,
                     std::string("photons or photon_power malformed: ") + e.what());
  }
  return ref;
}

}  // namespace

Action addPhotonsCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "photons",
      "Independent Monte Carlo reference: light tracing with per-patch tallies (no form factors, "
      "no mesh); writes patches.obj, radiosity.txt and standard_error.txt into a directory and "
      "optionally compares a `radiosity` run against it");
  struct State {
    std::string scene, output, compare, reference;
    PhotonOptions options;
    double sigmas = kDefaultSigmas, allowance = kDefaultAllowance, regionSize = kDefaultRegionSize;
    bool keepHidden = false;
    bool json = false, noContactSplit = false;
  };
  auto s = std::make_shared<State>();
  cmd->add_option("scene", s->scene, "Scene file (as `globalvis radiosity` reads it)")->required();
  cmd->add_option("-o,--output", s->output,
                  "Output directory (created if missing); required unless --reference is given");
  cmd->add_option("--photons", s->options.photons, "Photons shot in all")
      ->capture_default_str()
      ->check(CLI::Range(uint64_t{1000}, uint64_t{100'000'000'000}));
  cmd->add_option("--batches", s->options.batches,
                  "Independent batches (the standard errors come from their spread)")
      ->capture_default_str()
      ->check(CLI::Range(2, 4096));
  cmd->add_option("--seed", s->options.seed, "Random seed")->capture_default_str();
  cmd->add_option("--compare", s->compare,
                  "A `globalvis radiosity` output directory of the same scene: print the "
                  "area-weighted L2 of B-Ke over all patches, the solver-minus-photon relative "
                  "errors over the patch channels whose photon estimate is within 1 %, how many "
                  "channels were left out and why, leaks (lit patches where >= 10 photon hits "
                  "were expected and none came) and the worst region (exit code 1 on a leak or a "
                  "channel beyond --sigmas standard errors plus --allowance)")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--reference", s->reference,
                  "An earlier `photons` output directory of the same scene and options: compare "
                  "--compare against it instead of shooting photons again (to compare several "
                  "runs with one reference)")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--region-size", s->regionSize,
                  "With --compare: side of the region cubes (scene units) whose reflected power "
                  "is compared")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--sigmas", s->sigmas, "With --compare: allowed standard errors")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--allowance", s->allowance,
                  "With --compare: allowed relative error beyond the photon noise")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", s->json, "Print the statistics as JSON on stdout");
  addKeepHiddenFlag(*cmd, s->keepHidden);
  cmd->add_flag("--no-contact-split", s->noContactSplit,
                "Keep the patches whole (as `globalvis radiosity --no-contact-split`)");
  return [s] {
    const Scene scene = loadPipelineScene(s->scene, {!s->noContactSplit, s->keepHidden});
    if (scene.patches.empty()) throw InputError(s->scene, 0, "the scene has no patches");
    // Read the run to compare before the long work, so that a bad directory fails at once.
    std::vector<Rgb> solver;
    if (!s->compare.empty())
      solver = readRadiosityTxt((std::filesystem::path(s->compare) / "radiosity.txt").string(),
                                scene.patches.size());
    if (s->output.empty() && s->reference.empty())
      throw InputError(s->scene, 0, "photons needs -o DIR (or --reference DIR with --compare)");
    if (!s->reference.empty() && s->compare.empty())
      throw InputError(s->reference, 0, "--reference is only useful with --compare RUN");
    PhotonResult ref;
    double seconds = 0;
    nlohmann::json stats;
    std::filesystem::path dir;
    if (!s->reference.empty()) {
      ref = readPhotonReference(s->reference, scene.patches.size());
      stats = {{"reference", s->reference}, {"photons", ref.photons}};
      if (!s->output.empty()) dir = makeOutputDirectory(s->output);  // for stats.json only
    } else {
      dir = makeOutputDirectory(s->output);
      const auto t0 = Clock::now();
      const EmbreeScene bvh(scene);
      ref = photonReference(scene, bvh, s->options);
      seconds = secondsSince(t0);
      writeObj(scene, (dir / "patches.obj").string());
      const std::string what = fmt::format("{} photons in {} batches, seed {}", ref.photons,
                                           s->options.batches, s->options.seed);
      writePatchRgbTxt(ref.radiosity, "photon reference: radiosity per patch, " + what,
                       (dir / "radiosity.txt").string());
      writePatchRgbTxt(ref.standardError, "photon reference: standard error per patch, " + what,
                       (dir / "standard_error.txt").string());
      stats = {{"photons", ref.photons},
               {"batches", s->options.batches},
               {"seed", s->options.seed},
               {"rays", ref.rays},
               {"photon_power", {ref.photonPower.r, ref.photonPower.g, ref.photonPower.b}},
               {"seconds", seconds}};
    }
    int code = 0;
    if (!solver.empty()) {
      const PhotonComparison c =
          comparePhotons(scene, solver, ref, s->sigmas, s->allowance, s->regionSize);
      stats["comparison"] = {{"run", s->compare},
                             {"compared", c.compared},
                             {"beyond_tolerance", c.failures},
                             {"max_relative", c.maxRelative},
                             {"rms_relative", c.rmsRelative},
                             {"mean_signed", c.meanSigned},
                             {"area_weighted_signed", c.areaWeightedSigned},
                             {"worst_patch", c.worstPatch},
                             {"worst_channel", c.worstChannel},
                             {"sigmas", s->sigmas},
                             {"allowance", s->allowance},
                             {"l2_reflected", c.l2Reflected},
                             {"l2_photon_noise", c.l2PhotonNoise},
                             {"surfaces", c.surfaces},
                             {"twin_groups", c.twinGroups},
                             {"twin_patches", c.twinPatches},
                             {"channels", channelsJson(c.channels)},
                             {"leaks", leaksJson(c)},
                             {"regions", regionsJson(c)}};
      if (c.failures > 0 || c.channels.leaks > 0) code = 1;
    }
    if (!dir.empty()) writeJsonFile(stats, dir / "stats.json");
    if (s->json) {
      fmt::print("{}\n", stats.dump(2));
      return code;
    }
    if (!s->reference.empty())
      fmt::print("{} photons read from {}\n", ref.photons, s->reference);
    else
      fmt::print("{} photons, {} rays, {:.2f} s; wrote {}\n", ref.photons, ref.rays, seconds,
                 dir.string());
    if (stats.contains("comparison")) {
      const auto& c = stats["comparison"];
      fmt::print(
          "{} vs photons over {} patch channels: mean signed {:+.2f} % (area-weighted {:+.2f} "
          "%), RMS {:.2f} %, max {:.2f} % (patch {}), {} beyond {} sigma + {:.1f} %\n",
          s->compare, c["compared"].get<size_t>(), 100 * c["mean_signed"].get<double>(),
          100 * c["area_weighted_signed"].get<double>(), 100 * c["rms_relative"].get<double>(),
          100 * c["max_relative"].get<double>(), c["worst_patch"].get<size_t>(),
          c["beyond_tolerance"].get<size_t>(), s->sigmas, 100 * s->allowance);
      printCounts(c);
    }
    return code;
  };
}

}  // namespace gv::cli
