// `globalvis verify DIR`: checks DIR/visibility.txt against DIR/patches.obj by Embree ray casting
// (independent of propagation); prints the violations and exits 1 on any.
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "scene/patches_obj.h"
#include "visibility/verify.h"

namespace gv::cli {

Action addVerifyCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "verify",
      "Check a `vis` result (DIR/patches.obj + DIR/visibility.txt) by ray casting: no "
      "sampled sightline's pair missing, VISIBLE pairs unblocked, first hits in the "
      "blocker lists. Exit code 1 on any violation");
  struct State {
    std::string dir;
    VerifyOptions options;
    bool json = false;
  };
  auto s = std::make_shared<State>();
  cmd->add_option("dir", s->dir, "Output directory of `globalvis vis`")->required();
  cmd->add_option("--rays", s->options.rays, "Random rays from patches")
      ->check(CLI::Range(uint64_t{0}, uint64_t{1'000'000'000}));
  cmd->add_option("--segments", s->options.segments, "Random segments between listed pairs")
      ->check(CLI::Range(uint64_t{0}, uint64_t{1'000'000'000}));
  cmd->add_option("--seed", s->options.seed, "Random seed");
  cmd->add_option("--tightness-pairs", s->options.tightnessPairs,
                  "Listed pairs sampled for the tightness figure (48 segments each)")
      ->capture_default_str()
      ->check(CLI::Range(uint64_t{0}, uint64_t{100'000'000}));
  cmd->add_option("--contact", s->options.rayContact,
                  "Hits of the rays from patches closer than this fraction of the scene's "
                  "diagonal to their start are contact, not sight (1e-5 is the model "
                  "tolerance)")
      ->capture_default_str()
      ->check(CLI::Range(kVerifyContactDistance, 1e-3));
  cmd->add_option("--unlisted-pairs", s->options.unlistedPairs,
                  "Pairs not listed, drawn uniformly, each tried with up to 16 front-to-front "
                  "segments: a free one is a missing pair (finds small patches' misses, which "
                  "rays seldom reach)")
      ->capture_default_str()
      ->check(CLI::Range(uint64_t{0}, uint64_t{1'000'000'000}));
  cmd->add_flag("--json", s->json, "Print the report as JSON on stdout");
  return [s] {
    const std::filesystem::path dir(s->dir);
    const std::string objPath = (dir / "patches.obj").string();
    const Scene scene = importPatchesObj(objPath, "`globalvis vis`");
    const VisibilityGraph graph = readVisibilityTxt((dir / "visibility.txt").string());
    const VerifyReport v = verifyVisibility(scene, graph, s->options);
    if (s->json) {
      const nlohmann::json j = {
          {"dir", s->dir},
          {"rays", v.rays},
          {"rays_hitting_front", v.raysHittingFront},
          {"missing_pairs", v.missingPairs},
          {"segments", v.segments},
          {"blocked_segments", v.blockedSegments},
          {"blocked_visible", v.blockedVisible},
          {"missing_blockers", v.missingBlockers},
          {"offset_only_hits", v.offsetOnlyHits},
          {"contact_first_hits", v.contactFirstHits},
          {"contact_rays", v.contactRays},
          {"invalid_pairs", v.invalidPairs},
          {"unlisted_pairs_drawn", v.unlistedDrawn},
          {"unlisted_pairs_tried", v.unlistedTried},
          {"missing_unlisted_pairs", v.missingUnlisted},
          {"unlisted_pairs_through_cracks", v.unlistedThroughCracks},
          {"tightness_pairs", v.tightnessPairs},
          {"excess_pairs", v.excess},
          {"excess", v.tightnessPairs ? double(v.excess) / double(v.tightnessPairs) : 0.0},
          {"examples", v.examples},
          {"ok", v.ok()}};
      fmt::print("{}\n", j.dump(2));
      return v.ok() ? 0 : 1;
    }
    fmt::print("rays {} ({} met a patch's front first): pairs missing {}\n", v.rays,
               v.raysHittingFront, v.missingPairs);
    fmt::print(
        "segments {} between listed pairs ({} blocked): blocked VISIBLE pairs {}, "
        "first hits missing from blocker lists {}\n",
        v.segments, v.blockedSegments, v.blockedVisible, v.missingBlockers);
    if (v.offsetOnlyHits)
      fmt::print(
          "hits of segments moved {:g} of the diagonal off S and R that the segment between the "
          "sampled points does not cross (not violations): {}\n",
          kVerifyContactDistance, v.offsetOnlyHits);
    if (v.contactFirstHits)
      fmt::print(
          "unlisted hits of those segments behind a blocker the segment between the sampled "
          "points meets first, within that distance of its end (not violations): {}\n",
          v.contactFirstHits);
    if (v.contactRays)
      fmt::print(
          "rays whose first hit faces their patch from its own plane, within the model tolerance "
          "(faces in contact; not violations): {}\n",
          v.contactRays);
    if (v.invalidPairs) fmt::print("pairs naming patches that do not exist: {}\n", v.invalidPairs);
    if (v.unlistedDrawn)
      fmt::print(
          "unlisted pairs {} drawn ({} with a front-to-front segment, up to {} tried each): "
          "with a free segment (missing) {}\n",
          v.unlistedDrawn, v.unlistedTried, kUnlistedSegments, v.missingUnlisted);
    if (v.unlistedThroughCracks)
      fmt::print(
          "unlisted pairs free only through a gap narrower than {:g} of the diagonal beside a "
          "patch's edge (cracks the tolerance policy closes; not violations): {}\n",
          kVerifyContactDistance, v.unlistedThroughCracks);
    if (v.tightnessPairs)
      fmt::print(
          "tightness: {} of {} sampled listed pairs ({:.1f} %) have no free segment among {} "
          "(excess; at most 50 % means the list is at most about twice what rays see)\n",
          v.excess, v.tightnessPairs, 100.0 * double(v.excess) / double(v.tightnessPairs),
          kTightnessSegments);
    for (const std::string& e : v.examples) fmt::print("  {}\n", e);
    fmt::print("{}\n", v.ok() ? "OK: no violation" : "FAILED: violations found");
    return v.ok() ? 0 : 1;
  };
}

}  // namespace gv::cli
