// Benchmarks of the stabbing-line kernel (paper §4.1): one-shot tests of portal chains, with
// clipping + LP (the default), LP only and clipping only. Each checks known answers before timing
// and reports a hash of its answers so that a speed-up shows the answers did not change.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <vector>

#include "visibility/stabbing.h"

namespace gv {
namespace {

const Tolerance kTol{10.0};

void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "bench_stabbing: wrong answer: %s\n", what);
    std::abort();
  }
}

Winding rectZ(double x0, double x1, double y0, double y1, double z0) {
  return {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}};
}

// Seeded chains of `length` random convex portals stacked along +z, about half of them blocked.
std::vector<std::vector<Winding>> randomChains(int length, int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), u01(0, 1);
  std::vector<std::vector<Winding>> chains;
  for (int c = 0; c < count; ++c) {
    std::vector<Winding> seq;
    Vec3 center{};
    for (int i = 0; i < length; ++i) {
      const Vec3 n = normalize(Vec3{0.3 * u(rng), 0.3 * u(rng), 1});
      const Vec3 t0 = normalize(cross(n, {1, 0, 0})), t1 = cross(n, t0);
      const int k = 4 + static_cast<int>(u01(rng) * 4);
      Winding w;
      for (int j = 0; j < k; ++j) {
        const double a = 2 * std::numbers::pi * (j + 0.3 * u01(rng)) / k;
        w.push_back(center + t0 * std::cos(a) + t1 * std::sin(a));
      }
      seq.push_back(w);
      center += Vec3{0.7 * u(rng), 0.7 * u(rng), 1};
    }
    chains.push_back(seq);
  }
  return chains;
}

void checkKnownAnswers(const StabbingOptions& o) {
  const std::vector<Winding> straight{rectZ(0, 1, 0, 1, 0), rectZ(0, 1, 0, 1, 1),
                                      rectZ(0, 1, 0, 1, 2)};
  const std::vector<Winding> shifted{rectZ(0, 1, 0, 1, 0), rectZ(2, 3, 0, 1, 1),
                                     rectZ(0, 1, 0, 1, 2)};
  require(testPortalSequence(straight, kTol, o) != StabbingResult::Blocked, "straight chain");
  require(testPortalSequence(shifted, kTol, o) == StabbingResult::Blocked, "shifted chain");
}

void runChains(benchmark::State& state, StabbingOptions options) {
  checkKnownAnswers(options);
  const auto chains = randomChains(static_cast<int>(state.range(0)), 256, 42);
  uint64_t hash = 1469598103934665603ULL, blocked = 0;
  for (const auto& c : chains) {
    const StabbingResult r = testPortalSequence(c, kTol, options);
    hash = (hash ^ static_cast<uint64_t>(r)) * 1099511628211ULL;
    blocked += r == StabbingResult::Blocked;
  }
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(testPortalSequence(chains[i], kTol, options));
    i = (i + 1) % chains.size();
  }
  state.counters["blocked_of_256"] = static_cast<double>(blocked);
  state.counters["answer_hash_lo"] = static_cast<double>(hash & 0xffffff);
}

void BM_StabbingChainDefault(benchmark::State& s) { runChains(s, StabbingOptions{}); }
void BM_StabbingChainLpOnly(benchmark::State& s) { runChains(s, {false, true, false}); }
void BM_StabbingChainClipOnly(benchmark::State& s) { runChains(s, {true, false, false}); }
BENCHMARK(BM_StabbingChainDefault)->Arg(3)->Arg(6)->Arg(12);
BENCHMARK(BM_StabbingChainLpOnly)->Arg(3)->Arg(6)->Arg(12);
BENCHMARK(BM_StabbingChainClipOnly)->Arg(3)->Arg(6)->Arg(12);

}  // namespace
}  // namespace gv
