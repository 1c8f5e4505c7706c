// `globalvis photons SCENE -o DIR`: the independent light-tracing reference (photon_reference.h)
// with per-patch standard errors, and optionally a radiosity run compared against it.
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/scene_input.h"
#include "cli/output_files.h"
#include "radiosity/photon_comparison.h"
#include "radiosity/photon_reference.h"
#include "radiosity/radiosity_io.h"
#include "raycast/embree_scene.h"
#include "report/run_files.h"
#include "scene/scene_io.h"
#include "util/input_error.h"
#include "util/timing.h"

namespace gv::cli {

Action addPhotonsCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "photons",
      "Independent Monte Carlo reference: light tracing with per-patch tallies (no form factors, "
      "no mesh); writes patches.obj, radiosity.txt and standard_error.txt into a directory and "
      "optionally compares a `radiosity` run against it");
  struct State {
    std::string scene, output, compare;
    PhotonOptions options;
    double sigmas = 4, allowance = 0.01;
    bool keepHidden = false;
    bool json = false, noContactSplit = false;
  };
  auto s = std::make_shared<State>();
  cmd->add_option("scene", s->scene, "Scene file (as `globalvis radiosity` reads it)")->required();
  cmd->add_option("-o,--output", s->output, "Output directory (created if missing)")->required();
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
                  "solver-minus-photon relative errors over the patch channels whose photon "
                  "estimate is within 1 % (exit code 1 if any is beyond --sigmas standard errors "
                  "plus --allowance)")
      ->check(CLI::ExistingDirectory);
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
    const std::filesystem::path dir = makeOutputDirectory(s->output);
    const auto t0 = Clock::now();
    const EmbreeScene bvh(scene);
    const PhotonResult ref = photonReference(scene, bvh, s->options);
    const double seconds = secondsSince(t0);
    writeObj(scene, (dir / "patches.obj").string());
    const std::string what = fmt::format("{} photons in {} batches, seed {}", ref.photons,
                                         s->options.batches, s->options.seed);
    writePatchRgbTxt(ref.radiosity, "photon reference: radiosity per patch, " + what,
                     (dir / "radiosity.txt").string());
    writePatchRgbTxt(ref.standardError, "photon reference: standard error per patch, " + what,
                     (dir / "standard_error.txt").string());
    nlohmann::json stats = {{"photons", ref.photons},
                            {"batches", s->options.batches},
                            {"seed", s->options.seed},
                            {"rays", ref.rays},
                            {"seconds", seconds}};
    int code = 0;
    if (!solver.empty()) {
      const PhotonComparison c = comparePhotons(scene, solver, ref, s->sigmas, s->allowance);
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
                             {"allowance", s->allowance}};
      if (c.failures > 0) code = 1;
    }
    writeJsonFile(stats, dir / "stats.json");
    if (s->json) {
      fmt::print("{}\n", stats.dump(2));
      return code;
    }
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
    }
    return code;
  };
}

}  // namespace gv::cli
