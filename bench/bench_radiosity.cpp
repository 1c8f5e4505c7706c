// Benchmarks of hierarchical radiosity in `rays` mode (HSA91's baseline, paper §7.4) on the
// Cornell box and the default office. Each checks its answer first (energy bounds, convergence,
// lights at least their emission) and reports links, elements, rays and a hash of the per-patch
// radiosity, so a speed-up that changes the answer shows.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "generators/cornell_box.h"
#include "generators/office.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/ray_visibility.h"
#include "raycast/embree_scene.h"

namespace gv {
namespace {

void check(const Scene& scene, const RadiosityResult& r) {
  if (!r.stats.converged) throw std::runtime_error("radiosity did not converge");
  double emitted = 0, out = 0, maxRho = 0;
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const Material& m = scene.materials[scene.patches[p].material];
    const double a = scene.patches[p].polygon.area();
    const Rgb& b = r.patchRadiosity[p];
    if (b.r < m.emission.r || b.g < m.emission.g || b.b < m.emission.b)
      throw std::runtime_error("radiosity below emission");
    emitted += a * (m.emission.r + m.emission.g + m.emission.b);
    out += a * (b.r + b.g + b.b);
    maxRho = std::max({maxRho, m.reflectance.r, m.reflectance.g, m.reflectance.b});
  }
  if (!(out >= emitted && out <= emitted / (1 - maxRho))) throw std::runtime_error("energy bound");
}

uint64_t hashOf(const RadiosityResult& r) {
  uint64_t h = 1469598103934665603ull;
  for (const Rgb& c : r.patchRadiosity)
    for (double v : {c.r, c.g, c.b}) h = (h ^ static_cast<uint64_t>(std::llround(v * 1e6))) * 1099511628211ull;
  return h;
}

void run(benchmark::State& state, const Scene& scene, double epsilon) {
  const EmbreeScene bvh(scene);
  RadiosityOptions options;
  options.epsilon = epsilon;
  RadiosityResult last{{}, {}, ElementTree(scene), {}, {}};
  for (auto _ : state) {
    RayVisibility visibility(scene, bvh, 16);
    last = solveRadiosity(scene, visibility, options);
    benchmark::DoNotOptimize(last.patchRadiosity.data());
  }
  check(scene, last);
  const RadiosityStats& s = last.stats;
  state.counters["patches"] = static_cast<double>(s.patches);
  state.counters["links"] = static_cast<double>(s.rounds.back().links.total());
  state.counters["initial_links"] = static_cast<double>(s.rounds.front().links.total());
  state.counters["elements"] = static_cast<double>(s.rounds.back().elements);
  state.counters["interactions"] = static_cast<double>(s.interactions);
  state.counters["rays"] = static_cast<double>(s.rays);
  state.counters["rounds"] = static_cast<double>(s.rounds.size());
  state.counters["hash"] = static_cast<double>(hashOf(last) % 1000000007ull);
}

void BM_RadiosityRaysCornell(benchmark::State& state) {
  run(state, generateCornellBox(), 2e-5);
}
BENCHMARK(BM_RadiosityRaysCornell)->Unit(benchmark::kSecond)->Iterations(1);

void BM_RadiosityRaysOffice(benchmark::State& state) {
  run(state, generateOffice(), 2e-5);
}
BENCHMARK(BM_RadiosityRaysOffice)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace gv
