// Links between clusters of patches (patch_clusters.h): far groups of patches exchange their
// light through one link whose transfer is estimated by sampled segments, rather than through a
// link per pair with an exact form factor. The solver keeps a cluster link while a bound of the
// light it can carry stays under the BF threshold, and splits it otherwise, down to pairs of
// patches, which get ordinary links.
//
// How the light goes: Smits, Arvo & Greenberg (1994) and Sillion (1995) give a cluster one
// radiant intensity and its receivers one irradiance, which ignores which of a cluster's patches
// see each other: light from one room lands on the inward faces of a closed solid in the next.
// Here every sample is a segment from a point on a receiving patch to a point on a source patch,
// tested by the link oracle; only clear samples carry light, from the element the segment leaves
// to the patch it reaches. A patch that no clear segment reaches receives nothing through a
// cluster link, so the clusters do not open the leaks the oracles close.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "radiosity/element_tree.h"
#include "radiosity/link_visibility.h"
#include "radiosity/patch_clusters.h"

namespace gv {

/// A link between clusters x and y (not both the same; either may be a leaf, one patch).
struct ClusterLink {
  uint32_t x = 0, y = 0;
  uint32_t tapBegin = 0, tapCount = 0;  ///< its samples in the solver's ClusterTap store
};

/// One clear sample of a cluster link, in one direction: `receiver` (a patch) gathers
/// `coefficient` · B(source) per unit area (source: the deepest element at the segment's far end).
struct ClusterTap {
  uint32_t receiver = 0, source = 0;
  float coefficient = 0;
  StoredPoint at;  ///< the segment's far end: `source` is re-found there when it is cut further
};

/// The oracle's candidate pairs, looked up by pair or by pair of clusters (every pair when the
/// oracle says so). Kept as a row per patch, in the cluster tree's order, of its partners' tree
/// positions: a cluster is a range of positions, so whether two clusters hold a candidate pair
/// is a binary search per patch of the smaller one.
class CandidatePairs {
 public:
  CandidatePairs(LinkVisibility& visibility, const ClusterTree& clusters);
  /// The pair's tube, or nullopt when (a, b) is not a candidate (no light passes). a != b.
  std::optional<TubeId> find(uint32_t a, uint32_t b) const;
  /// Whether any patch of clusters x and any patch of y (ids in the tree given) form a candidate
  /// pair. None: the oracle proved every pair between them invisible (the visibility graph
  /// lists none, or their cells cannot see each other), so no light passes between the two
  /// clusters. x and y disjoint.
  bool anyBetween(uint32_t x, uint32_t y) const;
  /// How many pairs are candidates.
  size_t count() const { return count_; }

 private:
  /// Candidates by cells (LinkVisibility::candidateCells): per cluster, the cells its patches'
  /// fronts look into, and for clusters with many, the union of those cells' reach.
  void indexCells(const ClusterTree& clusters);
  bool cellsMaySee(uint32_t x, uint32_t y) const;

  /// The entries of the row at tree position `row`: partner position << 32 | tube, sorted.
  std::span<const uint64_t> row(uint32_t row) const {
    return std::span(entries_).subspan(rowBegin_[row], rowBegin_[row + 1] - rowBegin_[row]);
  }

  const ClusterTree* clusters_ = nullptr;  ///< the tree given (outlives this)
  bool every_ = false;
  size_t count_ = 0;
  std::vector<uint32_t> position_;  ///< per patch: its position in the tree's order
  std::vector<size_t> rowBegin_;    ///< per position (n + 1): its row's start in entries_
  std::vector<uint64_t> entries_;   ///< both directions of every pair

  const PatchCellReach* cells_ = nullptr;    ///< set: candidates by cells, nothing listed
  std::vector<size_t> clusterCellBegin_;     ///< per cluster (+ 1): its range in clusterCells_
  std::vector<uint32_t> clusterCells_;       ///< per cluster, its cells, sorted
  std::vector<uint8_t> clusterUnplaced_;     ///< per cluster: holds a patch placed in no cell
  std::vector<uint32_t> clusterReachIndex_;  ///< per cluster: index into clusterReach_, or none
  std::vector<CellSet> clusterReach_;
};

/// Clusters are linked only when the form factor from any point of one to the other is at most
/// this (by the bound A / (π d²)): a single sample then carries little, and the sampled transfer
/// stays close to its mean.
inline constexpr double kMaxClusterFormFactor = 0.05;

/// An upper bound of the light the link between x and y can carry, in either direction, as
/// reflected power: ρ_max(X) A_X B_max(Y) A_Y / (π d²), d the distance between the two boxes
/// (the form factor from a point to Y is at most A_Y / (π d²)); infinite when the clusters are
/// not well separated (kMaxClusterFormFactor). `brightX`, `brightY`: the largest radiosity over
/// each cluster.
double clusterTransferBound(const Cluster& x, const Cluster& y, double brightX, double brightY);

/// clusterTransferBound's two directions: the reflected power into x and into y (both infinite
/// when the clusters are not well separated).
struct ClusterTransfer {
  double intoX = 0, intoY = 0;
};
ClusterTransfer clusterTransfer(const Cluster& x, const Cluster& y, double brightX, double brightY);

/// How a cluster link picks the source patch of a sample: half the picks by area, half by power
/// (area × the patch's brightest radiosity channel when the link is sampled). By area alone, a
/// small bright emitter among large dim faces (a lamp panel under a ceiling beam, beside a wall)
/// is missed by almost every sample and hit by a rare one with a huge weight: on a lit level
/// one floor strip came out black and its neighbour 10 % too bright. The mixture keeps every
/// patch's probability at least half its area share, so the weights stay bounded (≤ 2 A_X) and
/// the estimate unbiased whatever the brightness.
class SourcePicker {
 public:
  /// `brightness`: per patch (scene order), ≥ 0.
  SourcePicker(const ClusterTree& clusters, std::span<const double> brightness);

  struct Pick {
    uint32_t patch = 0;
    double weight = 0;  ///< A_q / P(q): the picked patch's area over its probability
  };
  /// A patch of `cluster`, `u` in [0, 1).
  Pick pick(uint32_t cluster, double u) const;

 private:
  const ClusterTree& clusters_;
  std::vector<double> powerBefore_;  ///< running sums of area × brightness, in the tree's order
};

/// The clear samples of the link between clusters x and y: for every patch of either cluster,
/// `samplesPerPatch` segments from a stratified point on it to a point on the other cluster (its
/// patch picked by `sources`, the point uniform on it), weighted by the form-factor kernel and
/// tested with visibility.segmentBlocked (pairs that are not candidates are blocked). Unbiased:
/// the taps into a patch sum, in expectation, to its form factor to the other cluster,
/// visibility included. Deterministic per `seed`. Reads only: links may be sampled in parallel.
struct ClusterSampling {
  std::vector<ClusterTap> taps;
  uint64_t rays = 0;
};
ClusterSampling sampleClusterLink(const ClusterTree& clusters, const SourcePicker& sources,
                                  const ElementTree& elements, const CandidatePairs& candidates,
                                  const LinkVisibility& visibility, const Tolerance& tol,
                                  uint32_t x, uint32_t y, int samplesPerPatch, uint64_t seed);

}  // namespace gv
