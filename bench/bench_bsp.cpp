// Benchmarks of the spatial subdivision (paper §3, §7.1): BSP + portals on offices of growing
// size. Each checks its answer first (the cells' volumes fill the root box; every portal links
// two cells) and reports the §7.1 counts and a hash of them, so a speed-up that changes the
// result shows.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "bsp/subdivision.h"
#include "generators/office.h"

namespace gv {
namespace {

void check(const Subdivision& sub) {
  double volume = 0;
  for (const Cell& c : sub.cells) volume += c.shape.volume();
  const Vec3 e = sub.tree.root.bounds().extent();
  const double root = e.x * e.y * e.z;
  if (std::abs(volume - root) > 1e-8 * root) throw std::runtime_error("cells do not fill the root");
  for (const Portal& p : sub.portals) {
    if (p.back == p.front || p.back >= sub.cells.size() || p.front >= sub.cells.size())
      throw std::runtime_error("bad portal");
  }
}

uint64_t hashOf(const Subdivision& sub) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](uint64_t v) { h = (h ^ v) * 1099511628211ull; };
  for (const Cell& c : sub.cells) mix(c.shape.faces.size()), mix(c.patches.size());
  for (const Portal& p : sub.portals) mix(p.back), mix(p.front);
  return h;
}

/// BSP + portals for the office of about `state.range(0)` patches.
void BM_SubdivisionOffice(benchmark::State& state) {
  const Scene scene =
      generateOffice(officeOptionsForPatchCount(static_cast<size_t>(state.range(0))));
  {
    const Subdivision sub = buildSubdivision(scene);
    check(sub);
    state.counters["patches"] = static_cast<double>(scene.patches.size());
    state.counters["cells"] = static_cast<double>(sub.cells.size());
    state.counters["portals"] = static_cast<double>(sub.portals.size());
    state.counters["faces_per_cell"] = sub.stats.meanFacesPerCell;
    state.counters["coaffine_per_cell"] = sub.stats.meanCoaffinePatchesPerCell;
    state.counters["hash"] = static_cast<double>(hashOf(sub) % 1000000007ull);
  }
  double bsp = 0, portals = 0;
  for (auto _ : state) {
    const Subdivision sub = buildSubdivision(scene);
    bsp += sub.stats.bspSeconds;
    portals += sub.stats.portalSeconds;
    benchmark::DoNotOptimize(sub.portals.data());
  }
  state.counters["bsp_ms"] = 1e3 * bsp / static_cast<double>(state.iterations());
  state.counters["portal_ms"] = 1e3 * portals / static_cast<double>(state.iterations());
}
BENCHMARK(BM_SubdivisionOffice)
    ->Arg(400)
    ->Arg(1000)
    ->Arg(3000)
    ->Arg(10000)
    ->Arg(30000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gv
