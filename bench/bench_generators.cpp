// Benchmarks of scene generation: the office at the paper's scale (~400 patches) up to ~1M.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>

#include "generators/maze.h"
#include "generators/office.h"

namespace {

// FNV-1a over the patches' vertex coordinates: printed as a counter so that a faster generator
// can be seen to produce the same scene.
uint64_t sceneHash(const gv::Scene& scene) {
  uint64_t h = 1469598103934665603ull;
  for (const gv::Patch& p : scene.patches) {
    for (const gv::Vec3& v : p.polygon.vertices) {
      for (int i = 0; i < 3; ++i) {
        const auto bits = static_cast<uint64_t>(static_cast<int64_t>(v[i] * 1e6));
        h = (h ^ bits) * 1099511628211ull;
      }
    }
  }
  return h;
}

void BM_GenerateOffice(benchmark::State& state) {
  const auto target = static_cast<size_t>(state.range(0));
  const gv::OfficeOptions options = gv::officeOptionsForPatchCount(target);
  // Check the answer before timing it: the scene has the size it claims, near the target.
  const gv::Scene check = gv::generateOffice(options);
  if (check.patches.size() != gv::officePatchCount(options) ||
      check.patches.size() < target * 9 / 10 || check.patches.size() > target * 11 / 10) {
    state.SkipWithError("office patch count off target");
    return;
  }
  for (auto _ : state) {
    gv::Scene scene = gv::generateOffice(options);
    benchmark::DoNotOptimize(scene.patches.data());
  }
  state.counters["patches"] = static_cast<double>(check.patches.size());
  state.counters["floors"] = options.floors;
  state.counters["rows"] = options.rows;
  state.counters["columns"] = options.columns;
  state.counters["hash_low32"] = static_cast<double>(sceneHash(check) & 0xffffffffu);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(check.patches.size()));
}
BENCHMARK(BM_GenerateOffice)->Arg(400)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GenerateOffice)->Arg(100000)->Iterations(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GenerateOffice)->Arg(1000000)->Iterations(2)->Unit(benchmark::kMillisecond);

void BM_GenerateMaze(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const gv::MazeOptions options{.width = side, .height = side};
  size_t patches = 0;
  for (auto _ : state) {
    gv::Scene scene = gv::generateMaze(options);
    patches = scene.patches.size();
    benchmark::DoNotOptimize(scene.patches.data());
  }
  state.counters["patches"] = static_cast<double>(patches);
}
BENCHMARK(BM_GenerateMaze)->Arg(16)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond);

}  // namespace
