// Incremental blocker maintenance (paper §6.2): a tube's status from its blocker list (any
// occluder makes it INVISIBLE, all disjoint make it VISIBLE, else PARTIAL), the child tube's list
// as the parent's blockers reclassified, and the statistics of each outcome per refinement level.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "geometry/tolerance.h"
#include "linespace/blocker_geometry.h"
#include "linespace/tube.h"
#include "linespace/visibility_status.h"

namespace gv {

/// Sentinel: no proof blocker.
inline constexpr uint32_t kNoBlocker = std::numeric_limits<uint32_t>::max();

/// How many blocker classifications ended in each outcome.
struct OutcomeCounts {
  uint64_t occludes = 0, impinges = 0, disjoint = 0, punt = 0;
  uint64_t byPlanes = 0;      ///< of all, decided by plane tests alone (always Disjoint)
  uint64_t straddling = 0;    ///< of all, B's plane cut S or R (never Occludes)
  uint64_t puntsTested = 0;   ///< line tests said PUNT (then the stabbing test ran, if enabled)
  uint64_t puntsRemoved = 0;  ///< of those, the stabbing test proved disjoint
  /// Tubes found INVISIBLE by coplanar blockers jointly (no single one occluded); not counted
  /// in total(), which counts single-blocker classifications.
  uint64_t coplanarCovers = 0;
  uint64_t total() const { return occludes + impinges + disjoint + punt; }
  void add(const BlockerVerdict& v);
  OutcomeCounts& operator+=(const OutcomeCounts& o);
};

/// A classified tube: its status, the blockers that may still occlude it (a subset of the list
/// it was classified against, in the same order), and for INVISIBLE the blocker that proves it.
struct TubeVerdict {
  VisibilityStatus status = VisibilityStatus::Visible;
  std::vector<uint32_t> blockers;  ///< kept (Impinges or Punt); empty unless PARTIAL
  uint32_t proof = kNoBlocker;     ///< the occluding blocker of an INVISIBLE tube
  OutcomeCounts counts;            ///< this classification's outcomes
};

/// Classifies each blocker of `blockers` (ids into `table`) against the tube, stopping at the
/// first that occludes completely (INVISIBLE, that blocker the proof). VISIBLE when every one is
/// disjoint. Otherwise, with options.coplanarCover, a group of kept between blockers in one plane
/// that jointly covers the tube makes it INVISIBLE too (proof: the group's first blocker);
/// PARTIAL otherwise.
TubeVerdict classifyTube(const Tube& tube, std::span<const uint32_t> blockers,
                         const BlockerTable& table, const Tolerance& tol,
                         const TubeOptions& options = {});

/// Statistics of one refinement level (level = subdivisions from the patch pair: the sum of the
/// two elements' depths).
struct LevelStats {
  uint64_t tubes = 0;                                ///< tubes classified
  uint64_t visible = 0, partial = 0, invisible = 0;  ///< their statuses
  uint64_t inheritedVisible = 0;  ///< children of VISIBLE parents: VISIBLE with no work
  OutcomeCounts blockers;         ///< the blocker classifications
};

/// Per-level statistics of a whole refinement (index = level).
struct LinespaceStats {
  std::vector<LevelStats> levels;
  LevelStats& level(size_t l) {
    if (levels.size() <= l) levels.resize(l + 1);
    return levels[l];
  }
  /// Sums over all levels.
  LevelStats total() const;
};

}  // namespace gv
