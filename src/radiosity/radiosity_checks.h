// What a radiosity solution is checked for before a benchmark reports its time, and the hash of
// its answer, shared by `globalvis bench` (src/cli/bench_run.cpp) and the Google Benchmark kernels
// (bench/), so that their hashes can be compared.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "radiosity/hierarchical_radiosity.h"
#include "scene/scene.h"

namespace gv {

/// Which checks beyond the basic ones checkRadiosity makes.
struct RadiosityCheckOptions {
  /// The solver reported convergence (the kernels of bench/ run closed scenes to the end; the
  /// `bench` command's levels may stop at their round limit).
  bool converged = false;
  /// Σ A·B lies between the emitted power Σ A·E and Σ A·E / (1 − max ρ), summed over the channels:
  /// no light is made, and no more is reflected than a geometric series of the highest
  /// reflectance allows.
  bool energyBound = false;
};

/// The first problem of a solution as a message, or nullopt. Always: one value per patch, every
/// value finite and at least the patch's own emission (relative slack 1e-9 for the rounding of
/// the gather); then the checks `options` asks for.
std::optional<std::string> checkRadiosity(const Scene& scene, const RadiosityResult& r,
                                          const RadiosityCheckOptions& options = {});

/// FNV-1a 64 over the per-patch radiosity printed at 6 significant digits ("%.5e" per channel):
/// radiosity is a sum of floating-point terms, so the hash shows a changed answer, not a changed
/// summation order. `bench` prints it as 16 hex digits.
uint64_t radiosityHash(const RadiosityResult& r);

}  // namespace gv
