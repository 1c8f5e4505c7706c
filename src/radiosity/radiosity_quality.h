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
  /// RadiosityOptions::formFactor.relativeTolerance: the quadrature's error budget. 1e-2 left
  /// every figure of the Cornell box, the office and the furnished room unchanged against
  /// light tracing (L2, mean bias and per-patch RMS within 0.1 %) and cut the time by ~35 %: a
  /// link whose form factor varies by more than 1 % across its receiver is refined anyway.
  double formFactorTolerance;
  std::string_view summary;  ///< one line for --help
};

/// The levels, in order. Each is ~3x the links of the one before (measured on the office).
/// High is the CLI's default: per-patch RMS below 2 % against light tracing on the default
/// office (1.6 % measured) at ~1/3 of Max's time. Max is RadiosityOptions{}'s setting.
inline constexpr std::array<RadiosityQualityLevel, 5> kRadiosityQualityLevels{{
    {RadiosityQuality::Draft, "draft", 3e-3, 1e-2,
     "a preview: ~1-3 % L2, errors of 10-50 % on dim patches"},
    {RadiosityQuality::Low, "low", 1e-3, 1e-2, "~1-2 % L2, dim patches off by up to ~20-45 %"},
    {RadiosityQuality::Medium, "medium", 3e-4, 1e-2, "~1 % L2, per-patch RMS 2-5 %"},
    {RadiosityQuality::High, "high", 1e-4, 1e-2, "~0.5 % L2, per-patch RMS ~1.6-2.7 % (default)"},
    {RadiosityQuality::Max, "max", 2e-5, 1e-3, "~0.3 % L2, per-patch RMS ~1-2 %, ~3x high's time"},
}};

inline constexpr RadiosityQuality kDefaultRadiosityQuality = RadiosityQuality::High;

/// The level of `quality`.
constexpr const RadiosityQualityLevel& radiosityQualityLevel(RadiosityQuality quality) {
  return kRadiosityQualityLevels[static_cast<size_t>(quality)];
}

/// Sets the fields of `options` that `quality` decides (epsilon, the quadrature tolerance).
inline void applyRadiosityQuality(RadiosityQuality quality, RadiosityOptions& options) {
  const RadiosityQualityLevel& level = radiosityQualityLevel(quality);
  options.epsilon = level.epsilon;
  options.formFactor.relativeTolerance = level.formFactorTolerance;
}

/// The level named `name` (draft, low, medium, high, max), or nullopt.
constexpr std::optional<RadiosityQuality> parseRadiosityQuality(std::string_view name) {
  for (const RadiosityQualityLevel& level : kRadiosityQualityLevels)
    if (level.name == name) return level.quality;
  return std::nullopt;
}

}  // namespace gv
