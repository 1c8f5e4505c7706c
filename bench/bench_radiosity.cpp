// Benchmarks of hierarchical radiosity in `rays` and `shaft` modes (HSA91's baseline and Haines &
// Wallace's shafts, paper §7.4) on the Cornell box and the default office. Each checks its answer
// first (energy bounds, convergence, lights at least their emission) and reports links, elements,
// rays, a hash of the per-patch radiosity (a speed-up that changes the answer shows) and the RMS
// and mean relative error against a photon-tracing reference (8 M photons, computed once per
// scene outside the timing).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "generators/cornell_box.h"
#include "generators/office.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/radiosity_checks.h"
#include "radiosity/photon_reference.h"
#include "radiosity/ray_visibility.h"
#include "radiosity/shaft_visibility.h"
#include "raycast/embree_scene.h"

namespace gv {
namespace {

/// The shared checks (radiosity/radiosity_checks.h) with the two that hold for these closed
/// scenes run to the end: convergence and the energy bound. Throws on the first problem.
void checkSolution(const Scene& scene, const RadiosityResult& r) {
  if (auto problem = checkRadiosity(scene, r, {.converged = true, .energyBound = true}))
    throw std::runtime_error(*problem);
}

/// Relative error (per channel) of the solver against the photon reference over the patch
/// channels whose photon estimate is good to 1 %.
struct ErrorVsPhotons {
  double rms = 0, mean = 0, max = 0;
};

ErrorVsPhotons errorVsPhotons(const Scene& scene, const EmbreeScene& bvh, const std::string& key,
                              const std::vector<Rgb>& solver) {
  static std::map<std::string, PhotonResult> cache;
  auto it = cache.find(key);
  if (it == cache.end()) {
    PhotonOptions po;
    po.photons = 8'000'000;
    it = cache.emplace(key, photonReference(scene, bvh, po)).first;
  }
  const PhotonResult& ref = it->second;
  ErrorVsPhotons e;
  size_t n = 0;
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const double s[3] = {solver[p].r, solver[p].g, solver[p].b};
    const double m[3] = {ref.radiosity[p].r, ref.radiosity[p].g, ref.radiosity[p].b};
    const double d[3] = {ref.standardError[p].r, ref.standardError[p].g, ref.standardError[p].b};
    for (int c = 0; c < 3; ++c) {
      if (!(m[c] > 0) || d[c] > 0.01 * m[c]) continue;
      const double rel = s[c] / m[c] - 1;
      e.rms += rel * rel;
      e.mean += rel;
      e.max = std::max(e.max, std::abs(rel));
      ++n;
    }
  }
  if (n > 0) {
    e.rms = std::sqrt(e.rms / static_cast<double>(n));
    e.mean /= static_cast<double>(n);
  }
  return e;
}

void run(benchmark::State& state, const std::string& key, const Scene& scene, double epsilon,
         bool shaft, int rays = 16) {
  const EmbreeScene bvh(scene);
  RadiosityOptions options;
  options.epsilon = epsilon;
  RadiosityResult last{{}, {}, ElementTree(scene), {}, {}};
  for (auto _ : state) {
    std::unique_ptr<LinkVisibility> visibility;
    if (shaft)
      visibility = std::make_unique<ShaftVisibility>(scene, rays);
    else
      visibility = std::make_unique<RayVisibility>(scene, bvh, rays);
    last = solveRadiosity(scene, *visibility, options);
    benchmark::DoNotOptimize(last.patchRadiosity.data());
  }
  checkSolution(scene, last);
  const RadiosityStats& s = last.stats;
  state.counters["patches"] = static_cast<double>(s.patches);
  state.counters["links"] = static_cast<double>(s.rounds.back().links.total());
  state.counters["initial_links"] = static_cast<double>(s.rounds.front().links.total());
  state.counters["elements"] = static_cast<double>(s.rounds.back().elements);
  state.counters["interactions"] = static_cast<double>(s.interactions);
  state.counters["rays"] = static_cast<double>(s.rays);
  state.counters["rounds"] = static_cast<double>(s.rounds.size());
  state.counters["hash"] = static_cast<double>(radiosityHash(last) % 1000000007ull);
  const ErrorVsPhotons e = errorVsPhotons(scene, bvh, key, last.patchRadiosity);
  state.counters["rms_vs_photons"] = e.rms;
  state.counters["mean_vs_photons"] = e.mean;
  state.counters["max_vs_photons"] = e.max;
}

void BM_RadiosityRaysCornell(benchmark::State& state) {
  run(state, "cornell", generateCornellBox(), 2e-5, false);
}
BENCHMARK(BM_RadiosityRaysCornell)->Unit(benchmark::kSecond)->Iterations(1);

void BM_RadiosityShaftCornell(benchmark::State& state) {
  run(state, "cornell", generateCornellBox(), 2e-5, true);
}
BENCHMARK(BM_RadiosityShaftCornell)->Unit(benchmark::kSecond)->Iterations(1);

void BM_RadiosityRaysOffice(benchmark::State& state) {
  run(state, "office", generateOffice(), 2e-5, false);
}
BENCHMARK(BM_RadiosityRaysOffice)->Unit(benchmark::kSecond)->Iterations(1);

void BM_RadiosityShaftOffice(benchmark::State& state) {
  run(state, "office", generateOffice(), 2e-5, true);
}
BENCHMARK(BM_RadiosityShaftOffice)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace gv
