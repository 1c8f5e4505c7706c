// Benchmarks of hierarchical radiosity in the paper's `blockers` visibility mode (§6, §7.4) beside
// `rays` mode on the Cornell box and the default office: time, rays, links. The visibility graph
// (BSP + propagation) is built once outside the timing and its seconds reported as a counter.
// Each run checks its answer (convergence, energy bound, lights at least their emission) and
// reports a hash of the per-patch radiosity.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bsp/subdivision.h"
#include "generators/cornell_box.h"
#include "generators/office.h"
#include "radiosity/blocker_visibility.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/radiosity_checks.h"
#include "util/timing.h"
#include "visibility/propagation.h"

namespace gv {
namespace {

/// The shared checks (radiosity/radiosity_checks.h) with the two that hold for these closed
/// scenes run to the end: convergence and the energy bound. Throws on the first problem.
void checkSolution(const Scene& scene, const RadiosityResult& r) {
  if (auto problem = checkRadiosity(scene, r, {.converged = true, .energyBound = true}))
    throw std::runtime_error(*problem);
}

void run(benchmark::State& state, const Scene& scene, double minCoverage, bool resolvePunts) {
  BspOptions bsp;
  bsp.minCoverage = minCoverage;
  const auto t0 = Clock::now();
  const VisibilityGraph graph = computeVisibility(scene, buildSubdivision(scene, bsp));
  const double graphSeconds = secondsSince(t0);
  RadiosityOptions options;
  RadiosityResult last{{}, {}, ElementTree(scene), {}, {}};
  LevelStats totals;
  TubeOptions tubes;
  tubes.resolvePunts = resolvePunts;
  for (auto _ : state) {
    BlockerVisibility visibility(scene, graph, 16, tubes);
    last = solveRadiosity(scene, visibility, options);
    totals = visibility.stats().total();
    benchmark::DoNotOptimize(last.patchRadiosity.data());
  }
  checkSolution(scene, last);
  const RadiosityStats& s = last.stats;
  state.counters["graph_seconds"] = graphSeconds;
  state.counters["links"] = static_cast<double>(s.rounds.back().links.total());
  state.counters["links_partial"] = static_cast<double>(s.rounds.back().links.partial);
  state.counters["initial_links"] = static_cast<double>(s.rounds.front().links.total());
  state.counters["elements"] = static_cast<double>(s.rounds.back().elements);
  state.counters["interactions"] = static_cast<double>(s.interactions);
  state.counters["rays"] = static_cast<double>(s.rays);
  state.counters["blocker_tests"] = static_cast<double>(totals.blockers.total());
  state.counters["punts_removed"] = static_cast<double>(totals.blockers.puntsRemoved);
  state.counters["hash"] = static_cast<double>(radiosityHash(last) % 1000000007ull);
}

void BM_RadiosityBlockersCornell(benchmark::State& state) {
  run(state, generateCornellBox(), 0.0, state.range(0) != 0);
}
BENCHMARK(BM_RadiosityBlockersCornell)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

void BM_RadiosityBlockersOffice(benchmark::State& state) {
  run(state, generateOffice(), 0.3, state.range(0) != 0);
}
BENCHMARK(BM_RadiosityBlockersOffice)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace gv
