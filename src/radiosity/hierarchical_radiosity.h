// Hierarchical radiosity (Hanrahan, Salzman & Aupperle, SIGGRAPH 1991) with pluggable link
// visibility (paper §6, §7.4): links between elements carrying an exact unoccluded form factor
// times a visibility fraction, BF refinement, gather and push-pull, iterated to convergence.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "radiosity/element_tree.h"
#include "radiosity/form_factor.h"
#include "radiosity/link_visibility.h"
#include "scene/scene.h"

namespace gv {

/// A two-way link between elements a and b (HSA91 stores both directions; here one record holds
/// both, related by reciprocity A_a F_ab = A_b F_ba).
struct Link {
  uint32_t a = 0, b = 0;    ///< element ids
  double formFactorAB = 0;  ///< F(a → b) × visibility fraction: a gathers formFactorAB · B_b
  double formFactorBA = 0;  ///< F(b → a) × visibility fraction
  double unoccludedAB = 0;  ///< F(a → b) without visibility (an upper bound of the transfer)
  double variationA = 0;    ///< spread of the point form factor to b over a (FormFactorEstimate)
  double variationB = 0;    ///< spread of the point form factor to a over b
  float visibility = 1;     ///< the oracle's fraction
  VisibilityStatus status = VisibilityStatus::Visible;
  TubeId tube = kNoTube;
  double frontA = 1;     ///< fraction of a's area in front of b's plane (the part that exchanges)
  double frontB = 1;     ///< fraction of b's area in front of a's plane
  uint32_t samples = 0;  ///< rays the visibility came from (0: exact, e.g. no possible blocker)
  /// Partial links: the solver's taps (the oracle's clear samples mapped to the elements they
  /// end on) are tapBegin .. tapBegin + tapCount - 1 of its tap store; 0 taps: gather the means.
  uint32_t tapBegin = 0, tapCount = 0;
  /// The solver's cache of the per-child form-factor deviations at each end (receiver
  /// consistency); UINT32_MAX until first needed.
  uint32_t deviationsAtA = UINT32_MAX, deviationsAtB = UINT32_MAX;
  /// The solver's cache of each end's pieces as a source, weighed by the other end's kernel
  /// (source consistency); UINT32_MAX until first needed.
  uint32_t sourcePiecesOfA = UINT32_MAX, sourcePiecesOfB = UINT32_MAX;
};

/// Solver parameters. Defaults aim at converged answers (per-patch errors well below 1 %) on
/// scenes like the Cornell box and the default office in seconds, not at the fastest preview.
struct RadiosityOptions {
  /// BF refinement threshold (HSA91 §4.2, with an error bound in place of F): a link is refined
  /// while, in either direction, ρ_recv B_src A_recv δF exceeds `epsilon` times the total emitted
  /// power of the scene, δF being the link's form-factor error bound: the spread of the point
  /// form factor over the receiver for a Visible link (what handing the receiver one mean value
  /// misses), the whole unoccluded form factor for a Partial one (its visibility is a sample).
  /// B is the largest RGB channel. Relative, so it means the same in millimetres and in metres.
  double epsilon = 2e-5;
  /// Per patch, the emitted power its BF threshold is `epsilon` times, in place of the scene's
  /// total (empty: the total for every patch). A link is refined while the light it may get
  /// wrong into either end exceeds that end's threshold; a cluster link compares with the
  /// smallest of its patches'. Lets each room of a big building be judged against the lamps that
  /// can light it rather than against every lamp of the building (PatchCellReach::powerInView).
  std::vector<double> thresholdPower;
  /// Receiver-side consistency: links that pass the BF test but end at an element that other
  /// links have subdivided hand every descendant the element's mean form factor. Where the point
  /// form factor varies across it, leaves get too much or too little, their form factors no
  /// longer sum to what they should (in a closed box: 1), and as a leaf's error is the same as
  /// receiver and as source the solution is biased upward by ~ρ² Var / (1 − ρ) (measured 1 % at
  /// ρ = 0.7, 2.5 % at 0.9 in a furnace). Many small same-signed errors add up (a corner leaf
  /// under coarse links to far walls), so the bound is per element: the worst links at a
  /// subdivided element are refined into its existing children while the sum over its links of
  /// ρ B_src δF exceeds this fraction of its radiosity.
  double relativeEpsilon = 0.01;
  /// Source-side consistency, the mirror of relativeEpsilon: an element gathers each source's
  /// mean radiosity where its kernel weighs the source's parts unequally; summed over its links,
  /// ρ F (B_kernel-weighted − B_mean) must stay within this fraction of its radiosity (or of
  /// relativeEpsilon if smaller), else the links adding most are refined at the source. The
  /// ceiling over a lamp on lit-doom-fd2-map03 sees pillars bright at the bottom and dark at the
  /// top: +76 % against light tracing without the check, +36 % at 0.1, +16 % at 0.02, +12 % at
  /// 0.01 (`high` otherwise); 0.02 costs 10-30 % of the time on the lit levels.
  double sourceEpsilon = 0.02;
  /// Elements smaller than this fraction of the scene's total patch area are never subdivided.
  /// Only a floor under the BF test: 1e-5 stopped the walls next to a Quake level's 8-unit light
  /// cubes from resolving the hot spot (light_general.map: the cubes' faces 8 % dark against the
  /// photon tracer, RMS 1.72 %; at 1e-6 RMS 1.38 % for 8 % more time); on the office and the
  /// Cornell box the two give the same solution to the last digit.
  double minArea = 1e-6;
  /// A solve stops when no element's radiosity (any channel) changed by more than `tolerance`
  /// times the largest radiosity in the last Jacobi sweep.
  double tolerance = 1e-6;
  /// Refine/solve rounds at most (HSA91's outer loop); it stops earlier when a round refines
  /// no link.
  int maxRefinements = 12;
  /// Jacobi sweeps per solve at most (a safety net: convergence takes ~log(tol)/log(ρ_max)).
  int maxSweeps = 100000;
  uint64_t seed = 1;  ///< seeds every visibility sample (per link, so runs are deterministic)
  /// Worker threads of refinement and solves (oneTBB); 0: all hardware threads. The solution is
  /// the same, bit for bit, on any number.
  int threads = 0;
  /// Refinement stops making links once this many exist (links kept plus links waiting to be
  /// examined): links still over the BF threshold are then kept as they are, the run reports
  /// `linkBudgetReached` and is not converged. A guard against runs that would outgrow memory
  /// (~100-200 bytes per link with its taps; 20 M links: a few GB). A link between clusters
  /// counts an eighth of one.
  size_t maxLinks = 20'000'000;
  /// Clustering (patch_clusters.h, cluster_links.h): far groups of patches exchange light through
  /// one sampled link while a bound of what it carries stays under the BF threshold, so links
  /// grow about linearly rather than as n². The value is the samples per patch per direction of
  /// a cluster link; 0: no clustering, every candidate pair of patches gets an exact link at the
  /// top (HSA91). Oracles that cannot test single segments (`shaft`) run without clusters.
  int clusterSamples = 0;
  /// New cluster links are sampled this many at a time, their samples held meanwhile (the 100k
  /// office makes 10^8 in its first round). The solution does not depend on it.
  size_t clusterSamplingChunk = 4096;
  FormFactorOptions formFactor;
  /// A consistency pass after the round's first looks only at the elements whose links changed
  /// since the previous pass of its kind (the others keep their verdict: the radiosities stay
  /// put within a round). false: every pass looks at every element, for tests that check the
  /// two give the same solution.
  bool incrementalConsistency = true;
  /// Called with one line of progress per round (for stderr); may be empty.
  std::function<void(const std::string&)> progress;
  /// Called during each refinement round with (links of the round's start finished, their
  /// count), rising, at most once per step of a few thousand links and at the end; may be empty.
  std::function<void(size_t, size_t)> refineProgress;
};

/// What a run holds in all, per unit of RadiosityOptions::maxLinks (a link, or kClusterLinkShare
/// cluster links, counted with the links waiting to be made), rounded up from the 100k office
/// (`rays`, `high`): stopped at a budget of 31.6 M units in its first round, it peaked at 4.85 GB
/// resident (153 bytes per unit).
inline constexpr double kBytesPerLinkUnit = 160;

/// The link budget of a machine with `memoryBytes` of physical memory: as many units as 60 % of
/// it holds at kBytesPerLinkUnit, and never fewer than RadiosityOptions's default (20 M).
/// 23.5 GiB: 94.8 M, enough for the 100k office to converge (at 80 M it did, in 8.14 GB).
inline size_t linkBudgetForMemory(double memoryBytes) {
  const double units = 0.6 * memoryBytes / kBytesPerLinkUnit;
  const size_t floor = RadiosityOptions{}.maxLinks;
  return units > static_cast<double>(floor) ? static_cast<size_t>(units) : floor;
}

/// Link counts by the paper's visibility classes.
struct LinkCounts {
  size_t visible = 0, partial = 0, invisible = 0;
  size_t total() const { return visible + partial + invisible; }
};

/// One row of the paper's Table 1: what a refinement round did.
struct RefinementStats {
  int round = 0;  ///< 0 = the initial links
  /// Links made this round by class. Invisible ones are dropped when the oracle proved it (no
  /// rays); sampled ones are kept with fraction 0 (see Link::samples).
  LinkCounts created;
  LinkCounts links;         ///< links alive after the round
  size_t linksRefined = 0;  ///< links replaced by children this round
  /// Consistency passes run after the round's main pass (receiver and source passes, each
  /// counted; unless the link budget stopped them, the last of each found nothing to refine).
  size_t consistencyPasses = 0;
  size_t elements = 0;  ///< elements after the round (patches + all children)
  size_t leaves = 0;
  size_t interactions = 0;  ///< form factor + visibility evaluations this round
  uint64_t rays = 0;        ///< visibility rays cast this round
  double refineSeconds = 0;
  size_t clusterLinks = 0;  ///< cluster links alive after the round (clustering only)
  size_t clusterTaps = 0;   ///< their clear samples
  /// Cluster pairs dropped this round because the oracle lists no candidate pair between them.
  size_t clusterPairsInvisible = 0;
  int sweeps = 0;  ///< Jacobi sweeps of the solve that followed
  double solveSeconds = 0;
  /// Taps the solve moved off leaves they gave more than a hemisphere could (their clear
  /// samples concentrated there; Solver::liftConcentratedTaps), back to coarser pieces.
  size_t tapsLifted = 0;
};

/// Totals of a run.
struct RadiosityStats {
  std::string visibility;  ///< the oracle's name
  size_t patches = 0;
  size_t candidatePairs = 0;  ///< pairs the oracle proposed
  size_t facingPairs = 0;     ///< of which could face each other
  std::vector<RefinementStats> rounds;
  uint64_t rays = 0;
  size_t interactions = 0;
  double seconds = 0;
  bool converged = false;   ///< the last round refined nothing and the last solve met tolerance
  double emittedPower = 0;  ///< Σ A E over emitters (largest channel)
  int threads = 0;          ///< worker threads the solver ran on
  bool linkBudgetReached = false;  ///< refinement stopped at RadiosityOptions::maxLinks
  bool clustered = false;          ///< links between clusters of patches were used
};

/// The solution: radiosity per patch and the refined hierarchy with its links.
struct RadiosityResult {
  std::vector<Rgb> patchRadiosity;    ///< area-weighted mean radiosity of patch k
  std::vector<Rgb> elementRadiosity;  ///< per element id of `elements`
  ElementTree elements;
  std::vector<Link> links;
  RadiosityStats stats;
};

/// Solves the scene's radiosity. Exchange is one-sided: light leaves a patch's front and arrives
/// on a patch's front only. Emission is Material::emission (radiosity units), reflectance Kd.
RadiosityResult solveRadiosity(const Scene& scene, LinkVisibility& visibility,
                               const RadiosityOptions& options = {});

}  // namespace gv
