// Benchmarks of the geometry kernels (paper §3, §4.1): polygon and cell splitting, exact
// orient3d, Plücker side. Each checks its answer before timing and reports it as a counter.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/convex_polyhedron.h"
#include "geometry/plucker.h"
#include "geometry/predicates.h"

namespace gv {
namespace {

const Tolerance kTol{4.0};

/// A regular n-gon of radius 1 in z = 0.
ConvexPolygon regularPolygon(int n) {
  std::vector<Vec3> v;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    v.push_back({std::cos(a), std::sin(a), 0});
  }
  return *ConvexPolygon::fromVertices(v, kTol);
}

std::vector<Plane> randomPlanes(std::mt19937& rng, int count, double spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Plane> planes;
  while (static_cast<int>(planes.size()) < count) {
    const Vec3 n{u(rng), u(rng), u(rng)};
    if (length(n) > 0.1) planes.push_back(Plane::through(Vec3{u(rng), u(rng), u(rng)} * spread, n));
  }
  return planes;
}

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "benchmark self-check failed: %s\n", what);
    std::abort();
  }
}

void BM_PolygonSplit(benchmark::State& state) {
  const ConvexPolygon poly = regularPolygon(static_cast<int>(state.range(0)));
  std::mt19937 rng(1);
  const std::vector<Plane> planes = randomPlanes(rng, 1024, 0.7);
  for (const Plane& p : planes) {
    const PolygonSplit s = split(poly, p, kTol);
    const double a = (s.front ? s.front->area() : 0) + (s.back ? s.back->area() : 0);
    check(std::abs(a - poly.area()) < 1e-12, "polygon split areas sum to the whole");
  }
  std::size_t i = 0;
  for (auto _ : state) {
    PolygonSplit s = split(poly, planes[i++ & 1023], kTol);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PolygonSplit)->Arg(4)->Arg(16);

void BM_PolyhedronSplit(benchmark::State& state) {
  Aabb box;
  box.add({-1, -1, -1});
  box.add({1, 1, 1});
  // A cell with more faces than a box: the cube with its corners cut off.
  ConvexPolyhedron cell = *ConvexPolyhedron::fromAabb(box);
  for (int sx = -1; sx <= 1; sx += 2) {
    for (int sy = -1; sy <= 1; sy += 2) {
      for (int sz = -1; sz <= 1; sz += 2) {
        cell = *split(cell, Plane::through(Vec3(sx, sy, sz) * 0.8, {double(sx), double(sy), double(sz)}),
                      kTol)
                    .back;
      }
    }
  }
  check(cell.faces.size() == 14, "truncated cube has 14 faces");
  std::mt19937 rng(2);
  const std::vector<Plane> planes = randomPlanes(rng, 256, 0.5);
  for (const Plane& p : planes) {
    const PolyhedronSplit s = split(cell, p, kTol);
    const double v = (s.front ? s.front->volume() : 0) + (s.back ? s.back->volume() : 0);
    check(std::abs(v - cell.volume()) < 1e-9, "polyhedron split volumes sum to the whole");
  }
  std::size_t i = 0;
  for (auto _ : state) {
    PolyhedronSplit s = split(cell, planes[i++ & 255], kTol);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PolyhedronSplit);

/// Random points; `nearlyCoplanar` puts every fourth point almost on the plane of the previous
/// three, which forces the exact (slow) path of the filtered predicate.
std::vector<Vec3> orientPoints(bool nearlyCoplanar) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> pts;
  for (int i = 0; i < 4096; ++i) {
    if (nearlyCoplanar && i % 4 == 3) {
      const Vec3 &a = pts[pts.size() - 3], &b = pts[pts.size() - 2], &c = pts[pts.size() - 1];
      pts.push_back(a + (b - a) * u(rng) + (c - a) * u(rng));
    } else {
      pts.push_back({u(rng), u(rng), u(rng)});
    }
  }
  return pts;
}

void BM_Orient3dExact(benchmark::State& state) {
  const std::vector<Vec3> pts = orientPoints(state.range(0) != 0);
  check(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}) == 1, "orient3d convention");
  long sum = 0;
  for (std::size_t i = 0; i + 3 < pts.size(); i += 4) {
    sum += orient3d(pts[i], pts[i + 1], pts[i + 2], pts[i + 3]);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = (i++ & 1023) * 4;
    benchmark::DoNotOptimize(orient3d(pts[k], pts[k + 1], pts[k + 2], pts[k + 3]));
  }
  state.counters["signSum"] = static_cast<double>(sum);  // answer hash: changes if signs change
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Orient3dExact)->Arg(0)->Arg(1);

void BM_PluckerSide(benchmark::State& state) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Segment> segs(1024);
  std::vector<PluckerLine> lines(1024);
  for (std::size_t i = 0; i < segs.size(); ++i) {
    segs[i] = {{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    lines[i] = PluckerLine::of(segs[i]);
  }
  long sum = 0;
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    const double s = side(lines[i], lines[i + 1]);
    if (std::abs(s) > 1e-9) check((s > 0 ? 1 : -1) == sideExact(segs[i], segs[i + 1]), "side sign");
    sum += s > 0;
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1022;
    benchmark::DoNotOptimize(side(lines[k], lines[k + 1]));
  }
  state.counters["positive"] = static_cast<double>(sum);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PluckerSide);

void BM_PluckerSideExact(benchmark::State& state) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Segment> segs(1024);
  for (Segment& s : segs) s = {{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
  check(sideExact(segs[0], segs[0]) == 0, "a line meets itself");
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1022;
    benchmark::DoNotOptimize(sideExact(segs[k], segs[k + 1]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PluckerSideExact);

}  // namespace
}  // namespace gv
