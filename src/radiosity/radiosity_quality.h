// The user-facing accuracy setting of the radiosity solver (issue #19): five named points on
// its accuracy-time curve, each a BF refinement threshold (RadiosityOptions::epsilon).
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "radiosity/hierarchical_radiosity.h"

namespace gv {

/// From fastest to most accurate. The measured error and time of each on the Cornell box, the
/// default office and the furnished room are in docs/BENCHMARKS.md ("Radiosity: accuracy
/// against time").
enum class RadiosityQuality { Draft, Low, Medium, High, Max };

struct RadiosityQualityLevel {
  RadiosityQuality quality;
  std::string_view name;
  /// RadiosityOptions::epsilon: the BF threshold as a fraction of the total emitted power.
  double epsilon;
  /// RadiosityOptions::relativeEpsilon: the receiver-consistency bound. 0.05 or 0.1 in place of
  /// 0.01 at the same epsilon halved the links and the time on the office and the furnished
  /// room and left their error against light tracing as it was or lower (the room's per-patch
  /// RMS 3.2 -> 2.7 % at epsilon 1e-4): the tighter bound refines links whose errors mostly
  /// cancel.
  double relativeEpsilon;
  /// RadiosityOptions::formFactor.relativeTolerance: the quadrature's error budget. 1e-2 left
  /// every figure of the Cornell box, the office and the furnished room unchanged against
  /// light tracing (L2, mean bias and per-patch RMS within 0.1 %) and cut the time by ~35 %: a
  /// link whose form factor varies by more than 1 % across its receiver is refined anyway.
  double formFactorTolerance;
  /// RadiosityOptions::clusterSamples: links between clusters of patches below the BF
  /// threshold (0: a link per pair). On the lit real levels, `rays`, it cut the time 3-7x at the
  /// same error against light tracing (lit-doom-fd2-map03, 6.4k patches: 14 s, which without
  /// clusters did not finish); on the office, room and Cornell box it changed no figure by more
  /// than 0.1 %. Max links every pair: the reference.
  int clusterSamples;
  std::string_view summary;  ///< one line for --help
};

/// The levels, in order, chosen from a grid of (epsilon, relativeEpsilon) measured against light
/// tracing (docs/BENCHMARKS.md). High is the CLI's default: on the default office per-patch RMS
/// 1.83 % against 3.2·10^7 photons, mean bias -0.02 %, in 2.0-2.5 s on two cores (`blockers`),
/// a fifth of Max's time. Its relativeEpsilon was 0.1 until session 31: 2.00 % RMS, three
/// over-lit crevices carrying most of it, 10-15 % faster; the faster allocator
/// (src/cli/allocator.cpp) paid for the change. Max is RadiosityOptions{}'s setting, the one the
/// tests and earlier figures use.
inline constexpr std::array<RadiosityQualityLevel, 5> kRadiosityQualityLevels{{
    {RadiosityQuality::Draft, "draft", 1e-3, 0.1, 1e-2, 2, "a preview"},
    {RadiosityQuality::Low, "low", 3e-4, 0.05, 1e-2, 2, "L2 of B-Ke ~1-1.5 %"},
    {RadiosityQuality::Medium, "medium", 1e-4, 0.05, 1e-2, 2, "L2 ~0.5-1 %"},
    {RadiosityQuality::High, "high", 5e-5, 0.05, 1e-2, 2,
     "L2 ~0.4-0.6 %, per-patch RMS ~1.3-2.7 %; real levels ~1.2-3.5 %"},
    {RadiosityQuality::Max, "max", 2e-5, 0.01, 1e-3, 0,
     "the reference: a link per pair, no clusters; ~3-5x high's time, quadratic in patches"},
}};

inline constexpr RadiosityQuality kDefaultRadiosityQuality = RadiosityQuality::High;

/// The level of `quality`.
constexpr const RadiosityQualityLevel& radiosityQualityLevel(RadiosityQuality quality) {
  return kRadiosityQualityLevels[static_cast<size_t>(quality)];
}

/// Sets the fields of `options` that `quality` decides (epsilon, the consistency bound, the
/// quadrature tolerance, clustering).
inline void applyRadiosityQuality(RadiosityQuality quality, RadiosityOptions& options) {
  const RadiosityQualityLevel& level = radiosityQualityLevel(quality);
  options.epsilon = level.epsilon;
  options.relativeEpsilon = level.relativeEpsilon;
  options.formFactor.relativeTolerance = level.formFactorTolerance;
  options.clusterSamples = level.clusterSamples;
}

/// The level named `name` (draft, low, medium, high, max), or nullopt.
constexpr std::optional<RadiosityQuality> parseRadiosityQuality(std::string_view name) {
  for (const RadiosityQualityLevel& level : kRadiosityQualityLevels)
    if (level.name == name) return level.quality;
  return std::nullopt;
}

}  // namespace gv
