// `vis`'s choice of stop rule (buildVisibilitySubdivision): the first rule of
// kVisibilityCoverageSteps whose cells leave at most kMaxInteriorAreaFraction of the surface
// inside them, or the last before one that shatters the scene into more than
// kMaxPortalsPerPatch portals per patch if that one leaves no more than
// kShatterInteriorAreaFraction inside; checked against every rule built one by one.
#include <gtest/gtest.h>

#include "bsp/bsp_scenes.h"
#include "bsp/subdivision.h"
#include "generators/office.h"

namespace gv {
namespace {

using namespace bsptest;

enum class Ended { ByInteriorRule, ByPortalGuard, AtTheFinestRule };

/// The rule's choice, from each stop rule's subdivision built on its own.
std::pair<double, Ended> expectedRule(const Scene& scene) {
  double kept = -1, keptInside = 1;
  for (double coverage : kVisibilityCoverageSteps) {
    BspOptions o;
    o.minCoverage = coverage;
    const Subdivision sub = buildSubdivision(scene, o);
    if (kept >= 0 && keptInside <= kShatterInteriorAreaFraction &&
        double(sub.stats.portals) > kMaxPortalsPerPatch * double(sub.stats.patches))
      return {kept, Ended::ByPortalGuard};
    kept = coverage;
    keptInside = sub.stats.interiorAreaFraction;
    if (sub.stats.interiorAreaFraction <= kMaxInteriorAreaFraction)
      return {kept, Ended::ByInteriorRule};
  }
  return {kept, Ended::AtTheFinestRule};
}

TEST(VisibilitySubdivision, TakesTheFirstRuleLeavingLittleInsideUnlessItShatters) {
  std::vector<std::pair<std::string, Scene>> scenes;
  scenes.emplace_back("office", generateOffice(OfficeOptions{}));
  scenes.emplace_back("two rooms", twoRoomsWithDoor());
  scenes.emplace_back("messy", messy());
  for (uint32_t seed : {1u, 2u, 3u, 4u, 5u, 6u})
    scenes.emplace_back("clutter " + std::to_string(seed), randomClutter(seed, 12, 40));
  int byInterior = 0, byGuard = 0, belowCoarsest = 0;
  for (const auto& [name, scene] : scenes) {
    const auto [coverage, ended] = expectedRule(scene);
    const Subdivision sub = buildVisibilitySubdivision(scene, BspOptions{});
    BspOptions o;
    o.minCoverage = coverage;
    const Subdivision alone = buildSubdivision(scene, o);
    EXPECT_EQ(sub.stats.minCoverage, coverage) << name;
    EXPECT_EQ(sub.stats.cells, alone.stats.cells) << name;
    EXPECT_EQ(sub.stats.portals, alone.stats.portals) << name;
    byInterior += ended == Ended::ByInteriorRule;
    byGuard += ended == Ended::ByPortalGuard;
    belowCoarsest += coverage < kVisibilityCoverageSteps[0];
  }
  // The scenes exercise both ways of stopping and a rule finer than the coarsest.
  EXPECT_GT(byInterior, 0);
  EXPECT_GT(byGuard, 0);
  EXPECT_GT(belowCoarsest, 0);
}

}  // namespace
}  // namespace gv
