// Hierarchical radiosity: initial links, BF refinement, Jacobi gather with push-pull. HSA91 §4,
// paper §6 and §7.4 (Table 1 statistics per refinement round). On oneTBB: the work runs in
// parallel loops whose results land per index and are kept in a fixed order, so the solution is
// the same, bit for bit, on any number of threads.
#include "radiosity/hierarchical_radiosity.h"

#include <fmt/core.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>
#include <utility>

#include "radiosity/cluster_links.h"
#include "radiosity/patch_clusters.h"
#include "radiosity/polygon_sampling.h"
#include "util/check.h"
#include "util/parallel_for.h"
#include "util/timing.h"

namespace gv {
namespace {

Rgb operator+(const Rgb& x, const Rgb& y) {
  return {x.r + y.r, x.g + y.g, x.b + y.b};
}
Rgb operator*(const Rgb& x, const Rgb& y) {
  return {x.r * y.r, x.g * y.g, x.b * y.b};
}
Rgb operator*(double s, const Rgb& x) {
  return {s * x.r, s * x.g, s * x.b};
}
Rgb& operator+=(Rgb& x, const Rgb& y) {
  return x = x + y;
}
double maxChannel(const Rgb& x) {
  return x.maxChannel();
}

/// The rule of three: N agreeing samples bound the missed fraction by ~3 / N (95 %).
constexpr double kSampleBound = 3.0;

/// The most a leaf may gather through taps, as a sum of their coefficients: a hemisphere's
/// form factor. Over it, sampling has concentrated light on the leaf, and two such leaves
/// facing each other make the Jacobi sweeps diverge (Solver::refreshTaps).
constexpr double kMaxTapGather = 1.0;

/// Where a Partial link's light passes: one clear sample of its visibility, as the elements its
/// two ends lie in and the form factors that carry the sample's share of the link between them.
/// Each direction has its own pair: the source is the deepest element at the sample's end (its
/// radiosity there, not its parent's mean), the receiver the leaf there when the solve runs
/// (see refreshTaps; finishLink's coarser piece when that would concentrate light). A link
/// hands its receiver the source's mean radiosity, spread evenly; when part of the path is
/// blocked, the part of the source in view is often not its average and the lit part of the
/// receiver not all of it (a ceiling patch spanning a lit room and a dark corridor sees only
/// the room's floor). Gathering through the taps keeps that correlation: a one-room office was
/// 4.2 % dark against light tracing through the means, 1.6 % through taps. Shares sum to the
/// link's visibility fraction, so each element's total gather (its mean) is unchanged; only
/// where it lands and from where moves.
struct Tap {
  uint32_t a = 0, b = 0;  ///< receivers at the sample's ends (descendants of the link's a and b)
  uint32_t fromA = 0, fromB = 0;  ///< sources at the sample's ends (a's and b's deepest there)
  float intoA = 0;       ///< tap.a gathers intoA · B(tap.fromB): F_ab · share · A_a / A_tap.a
  float intoB = 0;       ///< tap.b gathers intoB · B(tap.fromA)
  StoredPoint atA, atB;  ///< the sample's ends, where fromA and fromB are re-found once cut further
  float share = 0;       ///< the sample's share of its link: the receiver's piece when lifted
};

/// A link to make between elements a and b, refining a link whose oracle state was `tube`;
/// `root`: which of the round's links it descends from (the progress count).
struct LinkJob {
  uint32_t a = 0, b = 0;
  TubeId tube = kNoTube;
  uint32_t root = 0;
};

/// Links decided (and jobs made) per step: each step evaluates its new links in parallel, then
/// keeps them in a fixed order. A constant, not a function of the thread count, so that which
/// links share a step, and so element ids, seeds and the whole solution, are the same on any
/// number of threads. Large enough to keep the cores busy (a step's jobs take tens of ms), small
/// enough that a step's clear samples take a few MB.
constexpr size_t kBatch = 8192;

/// A cluster link (16 bytes, and its few clear samples) counts this fraction of a link (~150
/// bytes with its taps and caches) against RadiosityOptions::maxLinks, a memory guard.
constexpr size_t kClusterLinkShare = 8;

/// Salts the seeds of cluster links, whose ids are cluster ids, apart from the element links'.
constexpr uint64_t kClusterSeed = 0xC105'7E55ull;

class Solver {
 public:
  Solver(const Scene& scene, LinkVisibility& visibility, const RadiosityOptions& options)
      : scene_(scene),
        visibility_(visibility),
        options_(options),
        tol_(scene.tolerance()),
        tree_(scene) {
    emission_.reserve(scene.patches.size());
    reflectance_.reserve(scene.patches.size());
    for (const Patch& p : scene.patches) {
      const Material& m = scene.materials.at(p.material);
      emission_.push_back(m.emission);
      reflectance_.push_back(m.reflectance);
    }
    radiosity_ = emission_;
    for (const Rgb& e : emission_) brightest_.push_back(maxChannel(e));
    gathered_.assign(scene.patches.size(), Rgb{});
    changedAt_.assign(scene.patches.size(), 0);
    double area = 0;
    for (size_t k = 0; k < scene.patches.size(); ++k) {
      area += tree_[static_cast<uint32_t>(k)].area;
      stats_.emittedPower += tree_[static_cast<uint32_t>(k)].area * maxChannel(emission_[k]);
    }
    minArea_ = options.minArea * area;
    threshold_ = options.epsilon * stats_.emittedPower;
    // Per patch, how much looser than threshold_ its own threshold is: 1 everywhere unless
    // thresholdPower says otherwise (so that the uniform case compares exactly as before).
    thresholdScale_.assign(scene.patches.size(), 1.0);
    if (!options.thresholdPower.empty()) {
      if (options.thresholdPower.size() != scene.patches.size())
        throw std::invalid_argument("thresholdPower: one value per patch expected");
      for (size_t k = 0; k < scene.patches.size(); ++k)
        if (options.thresholdPower[k] > 0 && stats_.emittedPower > 0)
          thresholdScale_[k] = options.thresholdPower[k] / stats_.emittedPower;
    }
    stats_.visibility = std::string(visibility.name());
    stats_.patches = scene.patches.size();
    if (options.clusterSamples > 0 && visibility.answersSegments() && scene.patches.size() >= 2) {
      clusters_.emplace(scene);
      stats_.clustered = true;
      clusterThresholdScale_.resize(clusters_->size());
      for (uint32_t c = 0; c < clusters_->size(); ++c) {
        double scale = INFINITY;
        for (uint32_t p : clusters_->patchesOf(c)) scale = std::min(scale, thresholdScale_[p]);
        clusterThresholdScale_[c] = scale;
      }
    }
  }

  RadiosityResult run() {
    const auto start = Clock::now();
    bool solved = false;
    {
      RefinementStats round;
      current_ = &round;
      const auto t0 = Clock::now();
      makeInitialLinks();
      finishRound(round, t0);
      solved = solve(round);
      report(round);
      stats_.rounds.push_back(round);
    }
    bool refinedNothing = false;
    for (int r = 1; r <= options_.maxRefinements; ++r) {
      RefinementStats round;
      round.round = r;
      current_ = &round;
      const auto t0 = Clock::now();
      refineLinks(round);
      compactTaps();
      finishRound(round, t0);
      if (round.linksRefined == 0) {
        refinedNothing = true;
        report(round);
        stats_.rounds.push_back(round);
        break;
      }
      solved = solve(round);
      report(round);
      stats_.rounds.push_back(round);
    }
    stats_.converged = refinedNothing && solved && !stats_.linkBudgetReached;
    for (const RefinementStats& r : stats_.rounds) {
      stats_.rays += r.rays;
      stats_.interactions += r.interactions;
    }
    stats_.seconds = secondsSince(start);

    RadiosityResult result{{}, radiosity_, std::move(tree_), std::move(links_), stats_};
    result.patchRadiosity.assign(radiosity_.begin(),
                                 radiosity_.begin() + static_cast<long>(scene_.patches.size()));
    return result;
  }

 private:
  /// The candidate pairs, a batch at a time (rays mode proposes every pair of patches).
  void makeInitialLinks() {
    if (clusters_) {
      candidates_.emplace(visibility_, *clusters_);
      stats_.candidatePairs = candidates_->count();
      std::vector<LinkJob> jobs;
      updateClusterBrightness();
      refineClusters({{0, 0}}, jobs);
      stats_.facingPairs += makeLinksInBatches(jobs, links_);
      return;
    }
    std::vector<LinkJob> jobs;
    auto flush = [&] {
      stats_.facingPairs += makeLinks(jobs, links_, nullptr);
      jobs.clear();
    };
    visibility_.forEachCandidatePair([&](uint32_t a, uint32_t b, TubeId tube) {
      ++stats_.candidatePairs;
      jobs.push_back({a, b, tube, 0});
      if (jobs.size() == kBatch) flush();
    });
    flush();
  }

  /// The unoccluded form factors of a link to make (HSA91), before its visibility.
  struct FormFactors {
    bool faces = false;  ///< false: the two cannot exchange light, no link
    double ab = 0;       ///< F(a → b)
    double variationA = 0, variationB = 0;
  };
  FormFactors formFactors(uint32_t a, uint32_t b) const {
    const Element& ea = tree_[a];
    const Element& eb = tree_[b];
    FormFactors f;
    if (!canFace(ea.polygon, eb.polygon, tol_.length())) return f;
    f.faces = true;
    // Integrate over the smaller element: the quadrature's accuracy depends on the integration
    // domain's size relative to the distance; reciprocity gives the other direction.
    if (eb.area < ea.area) {
      const FormFactorEstimate e =
          formFactorEstimate(eb.polygon, ea.polygon, tol_, options_.formFactor);
      f.ab = e.ab * eb.area / ea.area;
      f.variationA = e.variationB;
      f.variationB = e.variationA;
    } else {
      const FormFactorEstimate e =
          formFactorEstimate(ea.polygon, eb.polygon, tol_, options_.formFactor);
      f.ab = e.ab;
      f.variationA = e.variationA;
      f.variationB = e.variationB;
    }
    return f;
  }

  /// Makes the links of `jobs` that carry light: form factor (exact, unoccluded) times the
  /// oracle's visibility. The work runs in parallel, per job; the links, their taps and the
  /// round's counts are appended in job order (`out`, and each link's job root to `roots` if
  /// given), so nothing depends on the schedule. Returns how many jobs could face (interactions).
  size_t makeLinks(std::span<const LinkJob> jobs, std::vector<Link>& out,
                   std::vector<uint32_t>* roots) {
    std::vector<FormFactors> factors(jobs.size());
    parallelForEach(jobs.size(), [&](size_t i) { factors[i] = formFactors(jobs[i].a, jobs[i].b); });
    std::vector<uint32_t> asked;
    std::vector<LinkQuery> queries;
    size_t facing = 0;
    for (size_t i = 0; i < jobs.size(); ++i) {
      if (!factors[i].faces) continue;
      ++facing;
      if (!(factors[i].ab > 0)) continue;
      const LinkJob& j = jobs[i];
      asked.push_back(static_cast<uint32_t>(i));
      queries.push_back({&tree_[j.a], &tree_[j.b], j.tube, mixSeed(options_.seed, j.a, j.b)});
    }
    current_->interactions += facing;
    std::vector<VisibilityEstimate> estimates = visibility_.estimateAll(queries);
    CHECK(estimates.size() == queries.size());
    std::vector<std::optional<Link>> made(asked.size());
    std::vector<std::vector<Tap>> taps(asked.size());
    parallelForEach(asked.size(), [&](size_t k) {
      const LinkJob& j = jobs[asked[k]];
      made[k] = finishLink(j.a, j.b, factors[asked[k]], estimates[k], taps[k]);
    });
    for (size_t k = 0; k < asked.size(); ++k) {
      const VisibilityEstimate& v = estimates[k];
      current_->rays += v.raysCast;
      switch (v.status) {
        case VisibilityStatus::Invisible:
          ++current_->created.invisible;
          break;
        case VisibilityStatus::Partial:
          ++current_->created.partial;
          break;
        case VisibilityStatus::Visible:
          ++current_->created.visible;
          break;
      }
      if (!made[k]) continue;
      Link& link = *made[k];
      if (!taps[k].empty()) {
        link.tapBegin = static_cast<uint32_t>(taps_.size());
        link.tapCount = static_cast<uint32_t>(taps[k].size());
        taps_.insert(taps_.end(), taps[k].begin(), taps[k].end());
      }
      out.push_back(link);
      if (roots) roots->push_back(jobs[asked[k]].root);
    }
    return facing;
  }

  /// makeLinks on `jobs` kBatch at a time (each step's clear samples stay a few MB); returns how
  /// many could face.
  size_t makeLinksInBatches(std::span<const LinkJob> jobs, std::vector<Link>& out) {
    size_t facing = 0;
    for (size_t i = 0; i < jobs.size(); i += kBatch)
      facing += makeLinks(jobs.subspan(i, std::min(kBatch, jobs.size() - i)), out, nullptr);
    return facing;
  }

  /// The link between a and b from its form factors and visibility; nullopt when no light
  /// passes. A Partial link's taps go to `taps` (Link::tapBegin is set when they are stored).
  /// Reads the tree only: the links of a batch are finished in parallel.
  std::optional<Link> finishLink(uint32_t a, uint32_t b, const FormFactors& f,
                                 const VisibilityEstimate& v, std::vector<Tap>& taps) const {
    const Element& ea = tree_[a];
    const Element& eb = tree_[b];
    const double fab = f.ab;
    // Invisible, proven (no rays needed): no light passes. Sampled: light narrower than the
    // samples may pass; the link is kept, carrying nothing, so that refinement can look again
    // (dropping it would bias the solution dark, by p (1 - p)^N per link).
    if (v.status == VisibilityStatus::Invisible && v.raysCast == 0) return std::nullopt;
    Link link;
    // What fraction of each element lies in front of the other's plane (exchanges light).
    if (const std::optional<ExchangingParts> parts =
            exchangingParts(ea.polygon, eb.polygon, tol_)) {
      link.frontA = std::min(1.0, parts->a.area() / ea.area);
      link.frontB = std::min(1.0, parts->b.area() / eb.area);
    }
    link.a = a;
    link.b = b;
    link.unoccludedAB = fab;
    link.variationA = f.variationA;
    link.variationB = f.variationB;
    link.visibility = static_cast<float>(v.fraction);
    link.formFactorAB = fab * v.fraction;
    link.formFactorBA = fab * ea.area / eb.area * v.fraction;
    link.status = v.status;
    link.tube = v.tube;
    link.samples = static_cast<uint32_t>(std::min<uint64_t>(v.raysCast, UINT32_MAX));
    if (v.status == VisibilityStatus::Partial && !v.clearSamples.empty()) {
      const double fba = fab * ea.area / eb.area;
      taps.reserve(v.clearSamples.size());
      // A sample carries share w / fraction of the link's light; landing it in a piece smaller
      // than that share of the element concentrates it there: an irradiance many times the
      // unoccluded link's on a tiny element, rows of the gather summing over 1, and a solve that
      // diverges (lit-doom-fd2-map03 with clusters, whose pairs of patches are linked only after
      // the first round has cut them deep). So a tap starts no deeper than pieces of that
      // share: no tap hands its element more than the link's unoccluded form factor. Before
      // each solve, refreshTaps lands it at its leaf and liftConcentratedTaps brings back here
      // the taps that concentrate light.
      const double fraction = std::max(v.fraction, 1e-300);
      for (const ClearSample& c : v.clearSamples) {
        const double share = c.weight / fraction;
        const uint32_t ta = tree_.deepestContaining(a, c.from, ea.area * share);
        const uint32_t tb = tree_.deepestContaining(b, c.to, eb.area * share);
        const uint32_t sa = tree_.deepestContaining(ta, c.from);
        const uint32_t sb = tree_.deepestContaining(tb, c.to);
        taps.push_back({ta, tb, sa, sb,
                        static_cast<float>(fab * c.weight * ea.area / tree_[ta].area),
                        static_cast<float>(fba * c.weight * eb.area / tree_[tb].area),
                        StoredPoint(c.from), StoredPoint(c.to), static_cast<float>(share)});
      }
    }
    return link;
  }

  /// Whether the light the link between clusters x and y may carry exceeds, in either
  /// direction, the receiving cluster's threshold (its patches' smallest).
  bool clusterOverThreshold(uint32_t x, uint32_t y) const {
    const ClusterTransfer t =
        clusterTransfer((*clusters_)[x], (*clusters_)[y], clusterBright_[x], clusterBright_[y]);
    return t.intoX > threshold_ * clusterThresholdScale_[x] ||
           t.intoY > threshold_ * clusterThresholdScale_[y];
  }

  /// The BF error estimate (see RadiosityOptions::epsilon): reflected power the link may get
  /// wrong in either direction. Partial links count their whole unoccluded form factor: their
  /// visibility is a sample, and where it varies across the receiver is unknown.
  struct LinkError {
    double intoA = 0, intoB = 0;      ///< the form factor's spread over the receiver, or visibility
    double sourceA = 0, sourceB = 0;  ///< the source's radiosity varying under the kernel
    double clipA = 0, clipB = 0;      ///< the source's mean standing for a partly cut-off source
    double worst() const { return std::max(intoA + sourceA + clipA, intoB + sourceB + clipB); }
  };
  LinkError linkError(const Link& l) const {
    const Element& ea = tree_[l.a];
    const Element& eb = tree_[l.b];
    // A sampled visibility of 1 is uncertain: after N samples that all came through, the
    // fraction blocked can still be up to ~3 / N (the "rule of three", a 95 % bound). Without
    // this term, links that happened to sample all clear stop refining. (All blocked is just as
    // uncertain, and gets the whole bound: see below.)
    const double uncertain =
        l.samples == 0 ? 0.0 : std::min(1.0, kSampleBound / static_cast<double>(l.samples));
    const double ba = l.unoccludedAB, bb = l.unoccludedAB * ea.area / eb.area;
    double boundA = ba, boundB = bb;
    if (l.status == VisibilityStatus::Visible) {
      boundA = std::max(l.variationA, uncertain * ba);
      boundB = std::max(l.variationB, uncertain * bb);
    } else if (l.status == VisibilityStatus::Invisible && l.samples == 0) {
      boundA = boundB = 0;  // proven: nothing passes, nothing to refine
    }
    // Invisible by its samples (none got through): the whole unoccluded bound, as if one had. A
    // smaller bound for "all blocked" than for "some clear" makes the decision to look again
    // depend on the outcome: links between the two bounds were re-sampled (as children) when a
    // ray got through and kept at 0 when none did, so light through gaps narrower than the
    // samples was counted only in the outcomes that found it: expected (1 − (1 − p)^N) p F
    // instead of p F. On the 10k office `rays` that was a mean bias of −4.2 % (−0.2 % now),
    // on the default office −0.4 % (+0.15 %).
    LinkError e;
    // A partly visible source sends the mean radiosity of all of it, but only its visible part
    // counts, and that part may be the bright one (the floor of a lit room inside a floor patch
    // that spans dark corridors too): bound the source by its brightest leaf.
    const bool exact = l.status == VisibilityStatus::Visible;
    const double sourceB = exact ? maxChannel(radiosity_[l.b]) : brightest_[l.b];
    const double sourceA = exact ? maxChannel(radiosity_[l.a]) : brightest_[l.a];
    e.intoA = maxChannel(reflectance_[ea.patch]) * sourceB * ea.area * boundA;
    e.intoB = maxChannel(reflectance_[eb.patch]) * sourceA * eb.area * boundB;
    // A source partly behind the receiver's plane sends its mean radiosity, but only its front
    // part sends at all, and that part's radiosity can differ wholly from the rest (the floor
    // around and under a block seen from the block's side): up to B_src times the fraction cut
    // off. Only cutting the source helps.
    // The source side: a gathers b's mean radiosity, but the kernel weights b's parts unequally
    // (by up to variationB / F_ba relative); where b's radiosity varies by ΔB over its children,
    // a misses up to ρ_a A_a F_ab (variationB / F_ba) ΔB = ρ_a A_b variationB ΔB (the ceiling
    // over a lit room gathering a floor element whose bright part lies right below). Only
    // cutting b helps, and b's children exist, so it costs links only.
    e.sourceA = maxChannel(reflectance_[ea.patch]) * eb.area * l.variationB * radiosityRange(l.b);
    e.sourceB = maxChannel(reflectance_[eb.patch]) * ea.area * l.variationA * radiosityRange(l.a);
    e.clipA = maxChannel(reflectance_[ea.patch] * radiosity_[l.b]) * ea.area * ba * (1 - l.frontB);
    e.clipB = maxChannel(reflectance_[eb.patch] * radiosity_[l.a]) * eb.area * bb * (1 - l.frontA);
    // Each end's error measured against its own threshold (RadiosityOptions::thresholdPower),
    // in units of threshold_: which end is worse is then relative to what each may get wrong.
    const double scaleA = 1 / thresholdScale_[ea.patch], scaleB = 1 / thresholdScale_[eb.patch];
    e.intoA *= scaleA;
    e.sourceA *= scaleA;
    e.clipA *= scaleA;
    e.intoB *= scaleB;
    e.sourceB *= scaleB;
    e.clipB *= scaleB;
    return e;
  }

  /// How much an element's radiosity varies: the range over its children; for a leaf, what its
  /// own links say it should vary by (leafSpread_).
  double radiosityRange(uint32_t e) const {
    const Element& el = tree_[e];
    if (el.isLeaf()) return e < leafSpread_.size() ? leafSpread_[e] : 0.0;
    double lo = INFINITY, hi = -INFINITY;
    for (uint32_t c = el.firstChild; c < el.firstChild + el.childCount; ++c) {
      lo = std::min(lo, maxChannel(radiosity_[c]));
      hi = std::max(hi, maxChannel(radiosity_[c]));
    }
    return hi - lo;
  }

  /// A leaf holds one radiosity, but the light it gathers may vary across it: by up to
  /// ρ B_src δF per link ending at it, δF the spread of that link's point form factor over the
  /// leaf. As a source seen from close by, that unresolved variation is what a receiver gets
  /// wrong (a floor-to-ceiling post lit through a window above, gathered whole by the wall
  /// below the window: lit-doom-fd2-map03's patch 1052, +43 % against light tracing). Counting
  /// it in radiosityRange lets the source term cut such a leaf; the receiver-consistency pass
  /// then refines its incoming links into the pieces, which get their own values.
  void updateLeafSpread() {
    leafSpread_.assign(tree_.size(), 0.0);
    for (const Link& l : links_) {
      for (const bool atA : {true, false}) {
        const uint32_t e = atA ? l.a : l.b, other = atA ? l.b : l.a;
        if (!tree_[e].isLeaf()) continue;
        leafSpread_[e] += maxChannel(reflectance_[tree_[e].patch] * radiosity_[other]) *
                          (atA ? l.variationA : l.variationB);
      }
    }
  }

  bool canSplit(uint32_t e) const { return tree_[e].area >= minArea_; }

  /// HSA91's Refine: a link whose error exceeds the threshold is replaced by links
  /// from the children of one of its elements to the other; those are examined in turn (with the
  /// parent's radiosity, which children inherit). Which element: for a Visible link the receiver
  /// of the worse direction, since only cutting the receiver narrows the spread of the form
  /// factor across it; for a Partial link the larger one (HSA91's rule), which narrows the
  /// visibility sample most. Links are taken from a stack kBatch at a time: their verdicts in
  /// parallel (they read the radiosities, which new children inherit unchanged, so a verdict does
  /// not depend on what was split before it), the splits in stack order (element ids), the
  /// children's links in parallel and pushed in order (makeLinks).
  void refineLinks(RefinementStats& round) {
    updateLeafSpread();
    std::vector<Link> pending = std::move(links_);
    // The links come back one by one; grown by doubling, links_ copied every link already kept
    // and faulted in fresh pages at each step (at 10^7 links, half of a late round's time went
    // to copying, a quarter to page faults). Capacity never touched costs no resident memory,
    // so room for more than the round will make is reserved at once.
    links_ = std::vector<Link>();
    links_.reserve(pending.size() + pending.size() / 2 + kBatch);
    if (clusters_ && !stats_.linkBudgetReached) {
      // Cluster links whose bound now exceeds the threshold (the radiosities grew) are split;
      // the pairs of patches they reach join this round's links.
      updateClusterBrightness();
      // The bounds in parallel (millions of cluster links on big scenes), then the links over
      // the threshold taken out in order and the others kept in place.
      std::vector<char> over(clusterLinks_.size());
      parallelForEach(clusterLinks_.size(), [&](size_t i) {
        const ClusterLink& c = clusterLinks_[i];
        over[i] = clusterOverThreshold(c.x, c.y);
      });
      std::vector<std::pair<uint32_t, uint32_t>> split;
      size_t kept = 0;
      for (size_t i = 0; i < clusterLinks_.size(); ++i) {
        const ClusterLink& c = clusterLinks_[i];
        if (over[i]) {
          split.emplace_back(c.x, c.y);
          ++round.linksRefined;
        } else {
          clusterLinks_[kept++] = c;
        }
      }
      clusterLinks_.resize(kept);
      if (!split.empty()) {
        compactClusterTaps();
        std::vector<LinkJob> jobs;
        refineClusters(std::move(split), jobs);
        makeLinksInBatches(jobs, pending);
      }
    }
    refinePending(pending, round, true);
    std::vector<LinkJob> jobs;
    receiverPass_ = sourcePass_ = ConsistencyPass{};
    while (!stats_.linkBudgetReached &&
           (pushInconsistentLinks(jobs, round) || pushSourceInconsistentLinks(jobs, round))) {
      pending.clear();
      makeLinksInBatches(jobs, pending);
      jobs.clear();
      refinePending(pending, round, false);
    }
  }

  /// The largest leaf radiosity per cluster (children have larger ids than their parents).
  void updateClusterBrightness() {
    const ClusterTree& tree = *clusters_;
    clusterBright_.assign(tree.size(), 0.0);
    for (size_t k = tree.size(); k-- > 0;) {
      const Cluster& c = tree[static_cast<uint32_t>(k)];
      clusterBright_[k] = c.isLeaf() ? brightest_[tree.patchesOf(static_cast<uint32_t>(k))[0]]
                                     : std::max(clusterBright_[c.left], clusterBright_[c.right]);
    }
  }

  /// Refines the cluster pairs of `stack` (a cluster with itself stands for the pairs among its
  /// children): a pair whose bound is under the threshold becomes a cluster link; a pair of two
  /// patches over it becomes a job for an ordinary link (if the oracle lists the pair); any other
  /// pair is split at the cluster with the larger box. Sequential (bounds only, cheap); the new
  /// links' samples are then taken in parallel and kept in order. clusterBright_ must be
  /// current (updateClusterBrightness).
  void refineClusters(std::vector<std::pair<uint32_t, uint32_t>> stack,
                      std::vector<LinkJob>& jobs) {
    const ClusterTree& tree = *clusters_;
    // The new cluster links go straight to the end of clusterLinks_ and are sampled a chunk at a
    // time below: the 100k office makes 10^8 in its first round, and listing them twice with
    // all their samples held at once took its peak from 6.7 to 8.1 GB.
    const size_t first = clusterLinks_.size();
    while (!stack.empty()) {
      const auto [x, y] = stack.back();
      stack.pop_back();
      const Cluster& cx = tree[x];
      const Cluster& cy = tree[y];
      if (x == y) {
        if (!cx.isLeaf()) {
          stack.emplace_back(cx.left, cx.left);
          stack.emplace_back(cx.right, cx.right);
          stack.emplace_back(cx.left, cx.right);
        }
        continue;
      }
      // No candidate pair between them: the oracle proved every pair invisible (in `blockers`,
      // the visibility graph lists none), so the two exchange nothing, at any level below.
      if (!candidates_->anyBetween(x, y)) {
        ++current_->clusterPairsInvisible;
        continue;
      }
      if (links_.size() + jobs.size() + clusterLinks_.size() / kClusterLinkShare >=
          options_.maxLinks)
        stats_.linkBudgetReached = true;
      if (stats_.linkBudgetReached || !clusterOverThreshold(x, y)) {
        clusterLinks_.push_back({x, y});
        continue;
      }
      if (cx.isLeaf() && cy.isLeaf()) {
        const uint32_t p = tree.patchesOf(x)[0], q = tree.patchesOf(y)[0];
        if (const std::optional<TubeId> tube = candidates_->find(p, q))
          jobs.push_back({std::min(p, q), std::max(p, q), *tube, 0});
        continue;
      }
      const bool splitX = cy.isLeaf() || (!cx.isLeaf() && cx.box.diagonal() >= cy.box.diagonal());
      if (splitX) {
        stack.emplace_back(cx.left, y);
        stack.emplace_back(cx.right, y);
      } else {
        stack.emplace_back(x, cy.left);
        stack.emplace_back(x, cy.right);
      }
    }
    // Sources picked half by area, half by power as of now (brightest_'s first entries are the
    // patches' own elements).
    const SourcePicker sources(tree, std::span(brightest_).first(scene_.patches.size()));
    std::vector<ClusterSampling> sampled;
    const size_t chunk = std::max<size_t>(options_.clusterSamplingChunk, 1);
    for (size_t begin = first; begin < clusterLinks_.size(); begin += chunk) {
      const size_t count = std::min(chunk, clusterLinks_.size() - begin);
      sampled.assign(count, {});
      parallelForEach(count, [&](size_t i) {
        const ClusterLink& c = clusterLinks_[begin + i];
        sampled[i] = sampleClusterLink(tree, sources, tree_, *candidates_, visibility_, tol_, c.x,
                                       c.y, options_.clusterSamples,
                                       mixSeed(options_.seed ^ kClusterSeed, c.x, c.y));
      });
      for (size_t i = 0; i < count; ++i) {
        ClusterLink& c = clusterLinks_[begin + i];
        c.tapBegin = static_cast<uint32_t>(clusterTaps_.size());
        c.tapCount = static_cast<uint32_t>(sampled[i].taps.size());
        clusterTaps_.insert(clusterTaps_.end(), sampled[i].taps.begin(), sampled[i].taps.end());
        current_->rays += sampled[i].rays;
      }
    }
    current_->interactions += clusterLinks_.size() - first;
  }

  /// Drops the samples of cluster links that were split (they are only appended).
  void compactClusterTaps() {
    std::vector<ClusterTap> kept;
    for (ClusterLink& c : clusterLinks_) {
      const auto begin = static_cast<uint32_t>(kept.size());
      kept.insert(kept.end(), clusterTaps_.begin() + c.tapBegin,
                  clusterTaps_.begin() + c.tapBegin + c.tapCount);
      c.tapBegin = begin;
    }
    clusterTaps_ = std::move(kept);
  }

  /// Queues the links from the children of `split` (an end of `l`, with children) to l's other
  /// end.
  void replaceBy(const Link& l, uint32_t split, uint32_t root, std::vector<LinkJob>& jobs,
                 RefinementStats& round) const {
    ++round.linksRefined;
    const Element& parent = tree_[split];
    const uint32_t first = parent.firstChild, count = parent.childCount;
    for (uint32_t c = first; c < first + count; ++c)
      jobs.push_back(split == l.a ? LinkJob{c, l.b, l.tube, root} : LinkJob{l.a, c, l.tube, root});
  }

  /// Which end of `l` to subdivide, or kNoElement when the link is accurate enough (or neither
  /// end may be cut). Reads only.
  uint32_t splitOf(const Link& l) const {
    const LinkError error = linkError(l);
    if (error.worst() <= threshold_) return kNoElement;
    bool preferA = l.status == VisibilityStatus::Visible ? error.intoA >= error.intoB
                                                         : tree_[l.a].area >= tree_[l.b].area;
    // A source term dominating: cut that source (b for clipA / sourceA, a for B's).
    const double sourceOfA = error.clipA + error.sourceA, sourceOfB = error.clipB + error.sourceB;
    if (std::max(sourceOfA, sourceOfB) > std::max(error.intoA, error.intoB))
      preferA = sourceOfB >= sourceOfA;
    uint32_t split = preferA ? l.a : l.b;
    if (!canSplit(split)) split = preferA ? l.b : l.a;
    return canSplit(split) ? split : kNoElement;
  }

  /// Refines the links of `stack` (and their children, pushed on it) until each is accurate
  /// enough or cannot be cut; they end in links_. `report`: progress goes to refineProgress (the
  /// round's main pass; the consistency passes after it are not reported), counting the stack's
  /// first links whose descendants are all settled.
  void refinePending(std::vector<Link>& stack, RefinementStats& round, bool report) {
    const size_t total = stack.size();
    std::vector<uint32_t> roots(total);
    for (size_t i = 0; i < total; ++i) roots[i] = static_cast<uint32_t>(i);
    std::vector<uint32_t> outstanding(total, 1);  // per root: its links not yet settled
    size_t done = 0, reported = 0;
    std::vector<uint32_t> splits;
    std::vector<LinkJob> jobs;
    std::vector<Link> children;
    std::vector<uint32_t> childRoots;
    // Last in, first out, kBatch links at a time: children are examined before the rest of
    // their parents' generation, so the stack holds a few batches per level of the hierarchy
    // rather than a whole breadth-first level (on a 6.4k-patch level with 8 M initial links a
    // level held over 10^8 links: 28 GB asked for at once).
    while (!stack.empty()) {
      const size_t n = std::min(kBatch, stack.size());
      const size_t base = stack.size() - n;
      splits.resize(n);
      if (links_.size() + stack.size() + clusterLinks_.size() / kClusterLinkShare >=
          options_.maxLinks)
        stats_.linkBudgetReached = true;
      if (stats_.linkBudgetReached)
        std::fill(splits.begin(), splits.end(), kNoElement);
      else
        parallelForEach(n, [&](size_t i) { splits[i] = splitOf(stack[base + i]); });
      jobs.clear();
      for (size_t i = 0; i < n; ++i) {
        const Link& l = stack[base + i];
        if (splits[i] == kNoElement || !subdivide(splits[i])) {
          links_.push_back(l);
        } else {
          replaceBy(l, splits[i], roots[base + i], jobs, round);
        }
        // The main pass is followed by passes over every element; only the consistency
        // passes' own refinements need marking.
        if (!report) {
          touch(l.a);
          touch(l.b);
        }
      }
      children.clear();
      childRoots.clear();
      makeLinks(jobs, children, &childRoots);
      for (const uint32_t r : childRoots) ++outstanding[r];
      for (size_t i = 0; i < n; ++i)
        if (--outstanding[roots[base + i]] == 0) ++done;
      stack.resize(base);
      roots.resize(base);
      stack.insert(stack.end(), children.begin(), children.end());
      roots.insert(roots.end(), childRoots.begin(), childRoots.end());
      if (report && options_.refineProgress && done > reported) {
        reported = done;
        options_.refineProgress(done, total);
      }
    }
  }

  /// Receiver-side consistency (RadiosityOptions::relativeEpsilon). The links ending at a
  /// subdivided element hand each child the element's mean form factor; the child's own mean
  /// differs. Per child, the signed sum of those differences (estimated by the point form factor
  /// at the child's centroid), weighted by ρ B_src visibility, as a fraction of the element's
  /// radiosity, must stay within relativeEpsilon; otherwise the links adding most to the worst
  /// child's error are refined into the existing children until it fits. Errors of opposite
  /// sign cancel (a child nearer one source is farther from another), so only coherent ones (a
  /// corner child under coarse links to far walls) cost links. Replaces those links by the jobs
  /// of their children's links (`jobs`); returns whether any was replaced.
  bool pushInconsistentLinks(std::vector<LinkJob>& jobs, RefinementStats& round) {
    // The links at each subdivided, lit element, in link order (flat lists: linksAt[e] ..).
    const size_t n = tree_.size();
    std::vector<char> isExamined(n);
    parallelForEach(n, [&](size_t e) {
      isExamined[e] = !tree_[static_cast<uint32_t>(e)].isLeaf() && maxChannel(radiosity_[e]) > 0;
    });
    const std::vector<char> changed = changedSince(receiverPass_);
    auto looked = [&](uint32_t e) { return isExamined[e] != 0 && changed[e] != 0; };
    std::vector<uint32_t> linksAt(n + 1, 0);
    for (const Link& l : links_) {
      if (looked(l.a)) ++linksAt[l.a + 1];
      if (looked(l.b)) ++linksAt[l.b + 1];
    }
    for (size_t e = 0; e < n; ++e) linksAt[e + 1] += linksAt[e];
    // The same walk finds the ends looked at whose deviations are not yet known: a pass needs
    // only its own elements' (inconsistentLinksAt reads no other), and a second walk of every
    // link for them cost as much as this one.
    std::vector<uint32_t> ends(linksAt[n]);
    std::vector<LinkEnd> missing;
    {
      std::vector<uint32_t> at(linksAt.begin(), linksAt.end() - 1);
      for (uint32_t i = 0; i < links_.size(); ++i) {
        const Link& l = links_[i];
        if (looked(l.a)) {
          ends[at[l.a]++] = i;
          if (l.deviationsAtA == UINT32_MAX) missing.push_back({i, true});
        }
        if (looked(l.b)) {
          ends[at[l.b]++] = i;
          if (l.deviationsAtB == UINT32_MAX) missing.push_back({i, false});
        }
      }
    }
    computeChildDeviations(missing);
    // Per element, the links to refine, in parallel (each reads only); a link wanted at both
    // ends is split at the lower element id.
    std::vector<uint32_t> elements;
    for (uint32_t e = 0; e < n; ++e)
      if (linksAt[e + 1] > linksAt[e]) elements.push_back(e);
    std::vector<std::vector<uint32_t>> wanted(elements.size());
    tbb::enumerable_thread_specific<ConsistencyScratch> scratch;
    parallelForEach(elements.size(), [&](size_t x) {
      const uint32_t e = elements[x];
      wanted[x] = inconsistentLinksAt(
          e, std::span(ends).subspan(linksAt[e], linksAt[e + 1] - linksAt[e]), scratch.local());
    });
    std::vector<uint32_t> splitBy(links_.size(), kNoElement);
    bool any = false;
    for (size_t x = 0; x < elements.size(); ++x)
      for (const uint32_t i : wanted[x])
        if (splitBy[i] == kNoElement) {
          splitBy[i] = elements[x];
          any = true;
        }
    if (!any) return false;
    replaceLinksAt(splitBy, jobs, round);
    return true;
  }

  /// Replaces every link i with splitAt[i] != kNoElement by the jobs of its links from that
  /// end's children (replaceBy); keeps the others, in order.
  void replaceLinksAt(const std::vector<uint32_t>& splitAt, std::vector<LinkJob>& jobs,
                      RefinementStats& round) {
    size_t kept = 0;
    for (uint32_t i = 0; i < links_.size(); ++i) {
      if (splitAt[i] == kNoElement) {
        links_[kept++] = links_[i];
      } else {
        replaceBy(links_[i], splitAt[i], 0, jobs, round);
        touch(links_[i].a);
        touch(links_[i].b);
      }
    }
    links_.resize(kept);
  }

  /// Which elements a consistency pass must look at. Within a round the radiosities stay as the
  /// last solve left them, so an element's verdict can change only when its links do: one
  /// found consistent stays so, and one found inconsistent had links replaced (so changed).
  /// The round's first pass of each kind looks at every element; later ones at those changed
  /// since that kind's previous pass. (The 100k office ran ten passes a round, each a full
  /// walk of 12.7 M links for a handful of replaced ones: two thirds of a late round.)
  struct ConsistencyPass {
    bool everything = true;  ///< the round's first pass: every element
    uint32_t since = 0;      ///< else the elements with changedAt_ > since
  };

  /// Marks e's links as changed now.
  void touch(uint32_t e) { changedAt_[e] = stamp_; }

  /// Per element, whether `pass` must look at it; then starts the pass's next period.
  std::vector<char> changedSince(ConsistencyPass& pass) {
    ++current_->consistencyPasses;
    std::vector<char> changed(tree_.size(), 1);
    if (!pass.everything && options_.incrementalConsistency) {
      const uint32_t since = pass.since;
      parallelForEach(changed.size(), [&](size_t e) { changed[e] = changedAt_[e] > since; });
    }
    pass.everything = false;
    pass.since = stamp_++;
    return changed;
  }

  struct ConsistencyScratch {
    std::vector<double> contribution, deviation;
    std::vector<uint32_t> order;
    std::vector<char> taken;
  };

  /// The links (ids into links_) that must be refined into e's children for e's children to get
  /// within relativeEpsilon, most contributing first; `list`: the links at e. Reads only.
  std::vector<uint32_t> inconsistentLinksAt(uint32_t e, std::span<const uint32_t> list,
                                            ConsistencyScratch& s) const {
    std::vector<uint32_t> out;
    const Element& el = tree_[e];
    const double be = maxChannel(radiosity_[e]);
    const uint32_t k = el.childCount;
    const double budget = options_.relativeEpsilon;
    std::vector<double>& contribution = s.contribution;
    std::vector<double>& deviation = s.deviation;
    contribution.assign(list.size() * k, 0.0);
    deviation.assign(k, 0.0);
    s.taken.assign(list.size(), 0);
    for (size_t j = 0; j < list.size(); ++j) {
      const Link& l = links_[list[j]];
      const bool atA = l.a == e;
      const uint32_t other = atA ? l.b : l.a;
      const double weight =
          maxChannel(reflectance_[el.patch] * radiosity_[other]) * l.visibility / be;
      const double* offMean = deviationPool_.data() + (atA ? l.deviationsAtA : l.deviationsAtB);
      for (uint32_t c = 0; c < k; ++c)
        deviation[c] += contribution[j * k + c] = weight * offMean[c];
    }
    for (uint32_t pass = 0; pass <= k; ++pass) {
      uint32_t worst = 0;
      for (uint32_t c = 1; c < k; ++c)
        if (std::abs(deviation[c]) > std::abs(deviation[worst])) worst = c;
      if (std::abs(deviation[worst]) <= budget) break;
      const double sign = deviation[worst] > 0 ? 1.0 : -1.0;
      std::vector<uint32_t>& order = s.order;
      order.clear();
      for (uint32_t j = 0; j < list.size(); ++j)
        if (!s.taken[j] && sign * contribution[j * k + worst] > 0) order.push_back(j);
      std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) {
        const double cx = sign * contribution[x * k + worst],
                     cy = sign * contribution[y * k + worst];
        return cx != cy ? cx > cy : x < y;
      });
      for (uint32_t j : order) {
        if (std::abs(deviation[worst]) <= budget) break;
        for (uint32_t c = 0; c < k; ++c) deviation[c] -= contribution[j * k + c];
        s.taken[j] = 1;
        out.push_back(list[j]);
      }
    }
    return out;
  }

  /// An end of links_[link]: its a end (atA) or its b end.
  struct LinkEnd {
    uint32_t link;
    bool atA;
  };

  /// Per child c of each end e in `missing` (e with children): the link's mean form factor into
  /// e minus the point form factor at c's centroid. Geometry only, so computed once per link end
  /// and kept in deviationPool_ (Link::deviationsAtA/B): the consistency passes revisit the same
  /// links every pass and every round. Placed in the order of `missing`, computed in parallel.
  void computeChildDeviations(const std::vector<LinkEnd>& missing) {
    for (const LinkEnd& m : missing) {
      Link& l = links_[m.link];
      const uint32_t e = m.atA ? l.a : l.b;
      (m.atA ? l.deviationsAtA : l.deviationsAtB) = static_cast<uint32_t>(deviationPool_.size());
      deviationPool_.resize(deviationPool_.size() + tree_[e].childCount);
    }
    parallelForEach(missing.size(), [&](size_t m) {
      const Link& l = links_[missing[m].link];
      const bool atA = missing[m].atA;
      const uint32_t e = atA ? l.a : l.b, other = atA ? l.b : l.a;
      const Element& el = tree_[e];
      const double mean = atA ? l.unoccludedAB : l.unoccludedAB * tree_[l.a].area / tree_[l.b].area;
      double* out = deviationPool_.data() + (atA ? l.deviationsAtA : l.deviationsAtB);
      for (uint32_t c = 0; c < el.childCount; ++c)
        out[c] = mean - pointFormFactorToFront(tree_[el.firstChild + c].polygon.centroid(),
                                               el.polygon.plane, tree_[other].polygon, tol_);
    });
  }

  /// Source-side consistency, the mirror of pushInconsistentLinks: an element gathers each
  /// source's mean radiosity, but its kernel weighs the source's parts unequally, and where the
  /// source's radiosity varies the element gets the wrong value. Per link that error is small
  /// (linkError's sourceA/B, under the BF threshold), but it has the same sign at every link
  /// into an element whose sources all brighten the same way: a high ceiling over a lit room
  /// sees walls and pillars that are bright at the bottom, far from it, and dark at the top, next
  /// to it (lit-doom-fd2-map03: the ceilings over one lamp 50-70 % too bright, shrinking only
  /// to +31 % at a 25x finer BF threshold). So per receiving element the sum over its links of
  /// ρ F (B̃ − B̄) / B, B̃ the source's pieces' radiosity weighted by the point form factor from
  /// the element's centroid (computeSourceWeights) and B̄ their mean, must stay within
  /// RadiosityOptions::sourceEpsilon (or relativeEpsilon if smaller); otherwise the links adding
  /// most to it are refined at the source. Links with taps gather at their samples
  /// already and are left out. Returns whether any link was replaced (by `jobs`).
  bool pushSourceInconsistentLinks(std::vector<LinkJob>& jobs, RefinementStats& round) {
    std::vector<char> changed = changedSince(sourcePass_);
    // A link whose source was cut since the last pass has its pieces now: its receiver's sum
    // changes although its links did not.
    for (const auto& [link, ofA] : computeSourceWeights())
      changed[ofA ? links_[link].b : links_[link].a] = 1;
    struct Entry {
      uint32_t receiver = kNoElement, link = 0;
      double error = 0;  ///< relative to the receiver's radiosity, signed
    };
    // The links into a receiver looked at, in link order (so each receiver's sum adds the same
    // terms in the same order as over all links).
    std::vector<uint32_t> looked;
    for (uint32_t i = 0; i < links_.size(); ++i)
      if (links_[i].tapCount == 0 && (changed[links_[i].a] || changed[links_[i].b]))
        looked.push_back(i);
    std::vector<Entry> entries(2 * looked.size());
    parallelForEach(looked.size(), [&](size_t k) {
      const uint32_t i = looked[k];
      const Link& l = links_[i];
      for (const bool intoA : {true, false}) {
        const uint32_t receiver = intoA ? l.a : l.b, source = intoA ? l.b : l.a;
        if (!changed[receiver]) continue;
        const uint32_t at = intoA ? l.sourcePiecesOfB : l.sourcePiecesOfA;
        if (at == UINT32_MAX || !canSplit(source)) continue;
        Rgb weighted{};
        const uint32_t pieces = sourcePieces_[at].element;
        for (uint32_t c = 1; c <= pieces; ++c) {
          const double w = sourcePieces_[at + c].weight;
          const Rgb& b = radiosity_[sourcePieces_[at + c].element];
          weighted = {weighted.r + w * b.r, weighted.g + w * b.g, weighted.b + w * b.b};
        }
        const Rgb& mean = radiosity_[source];
        const Rgb& rho = reflectance_[tree_[receiver].patch];
        const Rgb& own = radiosity_[receiver];
        const double level = own.r + own.g + own.b;
        if (!(level > 0)) continue;
        const double f = intoA ? l.formFactorAB : l.formFactorBA;
        const double diff = rho.r * (weighted.r - mean.r) + rho.g * (weighted.g - mean.g) +
                            rho.b * (weighted.b - mean.b);
        entries[2 * k + (intoA ? 0 : 1)] = {receiver, i, f * diff / level};
      }
    });
    std::erase_if(entries, [](const Entry& e) { return e.receiver == kNoElement || e.error == 0; });
    std::vector<double> sum(tree_.size(), 0.0);
    for (const Entry& e : entries) sum[e.receiver] += e.error;
    const double budget = std::min(options_.relativeEpsilon, options_.sourceEpsilon);
    std::erase_if(entries, [&](const Entry& e) {
      return !(std::abs(sum[e.receiver]) > budget) || (e.error > 0) != (sum[e.receiver] > 0);
    });
    if (entries.empty()) return false;
    std::sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) {
      if (x.receiver != y.receiver) return x.receiver < y.receiver;
      if (std::abs(x.error) != std::abs(y.error)) return std::abs(x.error) > std::abs(y.error);
      return x.link < y.link;
    });
    std::vector<uint32_t> splitAt(links_.size(), kNoElement);
    for (const Entry& e : entries) {
      double& remaining = sum[e.receiver];
      if (!(std::abs(remaining) > budget)) continue;
      remaining -= e.error;
      const Link& l = links_[e.link];
      if (splitAt[e.link] == kNoElement) splitAt[e.link] = e.receiver == l.a ? l.b : l.a;
    }
    replaceLinksAt(splitAt, jobs, round);
    return true;
  }

  /// Per end e of a link with children: its pieces kSourcePieceDepth levels down (or leaves
  /// above that), each weighted by the point form factor from the other end's centroid (summing
  /// to 1; by area when e lies wholly behind it). A source's children alone can hide its
  /// variation: a floor-to-ceiling pillar face cut in two has two halves of the same mean when
  /// the lamp sits at the height of the cut, while a ceiling sees only the dark top of the upper
  /// half. Geometry only: kept in sourcePieces_ (Link::sourcePiecesOfA/B: a count, then the
  /// pieces), new ones computed in parallel. Returns the (link, of its a) ends it computed.
  std::vector<std::pair<uint32_t, bool>> computeSourceWeights() {
    struct Missing {
      uint32_t link;
      bool ofA;
      std::vector<uint32_t> pieces;
    };
    std::vector<Missing> missing;
    for (uint32_t i = 0; i < links_.size(); ++i) {
      const Link& l = links_[i];
      if (l.tapCount > 0) continue;
      for (const bool ofA : {true, false})
        if ((ofA ? l.sourcePiecesOfA : l.sourcePiecesOfB) == UINT32_MAX &&
            !tree_[ofA ? l.a : l.b].isLeaf())
          missing.push_back({i, ofA, {}});
    }
    // The pieces of each end in parallel (a walk down the tree per end, most of this pass's
    // time on big scenes when it ran serially), then placed in link order.
    parallelForEach(missing.size(), [&](size_t k) {
      Missing& m = missing[k];
      const Link& l = links_[m.link];
      std::vector<std::pair<uint32_t, uint32_t>> stack{{m.ofA ? l.a : l.b, 0}};
      while (!stack.empty()) {
        const auto [x, depth] = stack.back();
        stack.pop_back();
        const Element& el = tree_[x];
        if (el.isLeaf() || depth == kSourcePieceDepth) {
          m.pieces.push_back(x);
          continue;
        }
        for (uint32_t c = el.firstChild + el.childCount; c-- > el.firstChild;)
          stack.emplace_back(c, depth + 1);
      }
    });
    for (const Missing& m : missing) {
      Link& l = links_[m.link];
      (m.ofA ? l.sourcePiecesOfA : l.sourcePiecesOfB) = static_cast<uint32_t>(sourcePieces_.size());
      sourcePieces_.push_back({static_cast<uint32_t>(m.pieces.size()), 0});
      for (const uint32_t piece : m.pieces) sourcePieces_.push_back({piece, 0});
    }
    parallelForEach(missing.size(), [&](size_t k) {
      const Missing& m = missing[k];
      const Link& l = links_[m.link];
      const Element& e = tree_[m.ofA ? l.a : l.b];
      const Element& other = tree_[m.ofA ? l.b : l.a];
      SourcePiece* out = sourcePieces_.data() + (m.ofA ? l.sourcePiecesOfA : l.sourcePiecesOfB) + 1;
      const Vec3 x = other.polygon.centroid();
      double total = 0;
      for (size_t c = 0; c < m.pieces.size(); ++c)
        total += out[c].weight = static_cast<float>(
            pointFormFactorToFront(x, other.polygon.plane, tree_[m.pieces[c]].polygon, tol_));
      for (size_t c = 0; c < m.pieces.size(); ++c)
        out[c].weight = static_cast<float>(total > 0 ? out[c].weight / total
                                                     : tree_[m.pieces[c]].area / e.area);
    });
    std::vector<std::pair<uint32_t, bool>> filled;
    filled.reserve(missing.size());
    for (const Missing& m : missing) filled.emplace_back(m.link, m.ofA);
    return filled;
  }

  /// Drops the taps of links that refinement replaced (they are only appended).
  void compactTaps() {
    // Nothing to drop when every tap is still some link's (late rounds replace few links, and
    // copying the 100k office's taps took 1.5 s a round); where they lie does not matter.
    size_t used = 0;
    for (const Link& l : links_) used += l.tapCount;
    if (used == taps_.size()) return;
    std::vector<Tap> kept;
    kept.reserve(taps_.size());
    for (Link& l : links_) {
      if (l.tapCount == 0) continue;
      const auto begin = static_cast<uint32_t>(kept.size());
      kept.insert(kept.end(), taps_.begin() + l.tapBegin, taps_.begin() + l.tapBegin + l.tapCount);
      l.tapBegin = begin;
    }
    taps_ = std::move(kept);
  }

  bool subdivide(uint32_t e) {
    const bool had = !tree_[e].isLeaf();
    if (!tree_.subdivide(e)) return false;
    if (!had) {
      // New elements start with their parent's radiosity (what push-pull would give them).
      const Rgb inherited = radiosity_[e];
      radiosity_.resize(tree_.size(), inherited);
      brightest_.resize(tree_.size(), brightest_[e]);
      gathered_.resize(tree_.size(), Rgb{});
      changedAt_.resize(tree_.size(), stamp_);
    }
    return true;
  }

  /// A tap reads its source's radiosity at the sample's end: the deepest element there when the
  /// tap was made. Refinement cuts sources further afterwards (other links ask for it), and the
  /// tap would go on reading the mean of the whole piece: on q3-dm4ish a wall facing the void
  /// saw, through 5 clear samples, the dark overhanging end of a 205-unit ceiling whose lit end
  /// was cut into 240 leaves later, and gathered the whole ceiling's mean, 40x its end's
  /// radiosity (a patch lit where light tracing found none). So before each solve every tap's
  /// source descends to the deepest element at its point.
  ///
  /// The receivers land at the deepest element at their point too: the light a sample carries
  /// arrives where the sample ended. Landing it over a piece of its link's end (makeLink's rule,
  /// pieces of the sample's share of the link) spreads the light that enters a slot at its
  /// mouth over the slot's depth, where it escapes less often: the slot then traps light, and
  /// the back of a cabinet standing 0.089 from a wall was twice as bright as light tracing in
  /// its middle (bench/scenes/cabinet_slot.obj). Landing at a point can concentrate one tap's
  /// light on a leaf far smaller than its stratum, so that the leaf gathers more than a whole
  /// hemisphere could give it (coefficients summing over 1) and the solve diverges (it did on
  /// q3-sleekgrinder, whose run grew to 6.7 GB): liftConcentratedTaps puts the taps of such
  /// leaves back at makeLink's rule.
  void refreshTaps() {
    auto descend = [&](uint32_t& source, const StoredPoint& at) {
      if (!tree_[source].isLeaf()) source = tree_.deepestContaining(source, at.point());
    };
    parallelForEach(links_.size(), [&](size_t i) {
      const Link& l = links_[i];
      for (uint32_t t = l.tapBegin; t < l.tapBegin + l.tapCount; ++t) {
        Tap& tap = taps_[t];
        landTap(tap.a, tap.intoA, tap.atA);
        landTap(tap.b, tap.intoB, tap.atB);
        descend(tap.fromA, tap.atA);
        descend(tap.fromB, tap.atB);
      }
    });
    parallelForEach(clusterTaps_.size(),
                    [&](size_t t) { descend(clusterTaps_[t].source, clusterTaps_[t].at); });
  }

  /// Moves a tap's receiver down to the leaf at its point, the coefficient rescaled to the new
  /// receiver's area (the same light over a smaller piece).
  void landTap(uint32_t& receiver, float& into, const StoredPoint& at) const {
    if (tree_[receiver].isLeaf()) return;
    const uint32_t leaf = tree_.deepestContaining(receiver, at.point());
    into = static_cast<float>(into * tree_[receiver].area / tree_[leaf].area);
    receiver = leaf;
  }

  /// Moves a tap's receiver up from where it landed to its first ancestor no smaller than
  /// `minArea` (at most `end`, its link's end), the coefficient rescaled. Up the receiver's own
  /// path: found again from `end` through the single-precision point, rounding at a shared edge
  /// could pick a sibling's branch. Returns whether it moved.
  bool liftTap(uint32_t& receiver, float& into, uint32_t end, double minArea) const {
    uint32_t e = receiver;
    while (e != end && tree_[e].area < minArea) e = tree_[e].parent;
    if (e == receiver) return false;
    into = static_cast<float>(into * tree_[receiver].area / tree_[e].area);
    receiver = e;
    return true;
  }

  /// After refreshTaps: the leaves whose taps alone give them more than a whole hemisphere
  /// could (their coefficients summing over kMaxTapGather) have had light concentrated on them
  /// by sampling; their taps go back to makeLink's rule, pieces of their sample's share of the
  /// link's end, up their own path (liftTap): no leaf gains a tap, so one pass suffices. Counts
  /// the taps moved.
  void liftConcentratedTaps(RefinementStats& round) {
    // Summed from all threads in any order: in fixed point, so that the sums, and the taps
    // lifted, are the same on any number of threads.
    constexpr double kOne = 4294967296.0;  // 2^32
    // Each term clamped just over the limit: the test is "over it", and 2^31 terms at the clamp
    // cannot wrap the sum.
    auto fixed = [](float c) {
      return c > 0 ? static_cast<uint64_t>(std::min<double>(c, 2 * kMaxTapGather) * kOne)
                   : uint64_t{0};
    };
    std::vector<std::atomic<uint64_t>> gather(tree_.size());
    parallelForEach(links_.size(), [&](size_t i) {
      const Link& l = links_[i];
      for (uint32_t t = l.tapBegin; t < l.tapBegin + l.tapCount; ++t) {
        gather[taps_[t].a].fetch_add(fixed(taps_[t].intoA), std::memory_order_relaxed);
        gather[taps_[t].b].fetch_add(fixed(taps_[t].intoB), std::memory_order_relaxed);
      }
    });
    parallelForEach(clusterTaps_.size(), [&](size_t t) {
      gather[clusterTaps_[t].receiver].fetch_add(fixed(clusterTaps_[t].coefficient),
                                                 std::memory_order_relaxed);
    });
    const auto limit = static_cast<uint64_t>(kMaxTapGather * kOne);
    auto over = [&](uint32_t e) {
      return tree_[e].isLeaf() && gather[e].load(std::memory_order_relaxed) > limit;
    };
    std::vector<uint32_t> lifted(links_.size(), 0);
    parallelForEach(links_.size(), [&](size_t i) {
      const Link& l = links_[i];
      for (uint32_t t = l.tapBegin; t < l.tapBegin + l.tapCount; ++t) {
        Tap& tap = taps_[t];
        if (over(tap.a) && liftTap(tap.a, tap.intoA, l.a, tree_[l.a].area * tap.share)) ++lifted[i];
        if (over(tap.b) && liftTap(tap.b, tap.intoB, l.b, tree_[l.b].area * tap.share)) ++lifted[i];
      }
    });
    for (const uint32_t n : lifted) round.tapsLifted += n;
  }

  /// Who gathers what, per receiving element e: the terms linkBegin[e] .. linkBegin[e + 1] of
  /// `linkTerms` (from the links without taps) and tapBegin[e] .. tapBegin[e + 1] of `tapTerms`,
  /// each a source and the coefficient e gathers its radiosity with, in link order. Built once per
  /// solve, so that a sweep is a loop over receivers, in parallel, each adding its terms in a
  /// fixed order (a loop over links would add into shared sums).
  struct GatherLists {
    std::vector<uint32_t> linkBegin, tapBegin;
    std::vector<std::pair<uint32_t, double>> linkTerms;
    std::vector<std::pair<uint32_t, float>> tapTerms;
  };
  GatherLists gatherLists() const {
    GatherLists g;
    const size_t n = tree_.size();
    g.linkBegin.assign(n + 1, 0);
    g.tapBegin.assign(n + 1, 0);
    for (const Link& l : links_) {
      if (l.tapCount == 0) {
        ++g.linkBegin[l.a + 1];
        ++g.linkBegin[l.b + 1];
        continue;
      }
      for (uint32_t t = l.tapBegin; t < l.tapBegin + l.tapCount; ++t) {
        ++g.tapBegin[taps_[t].a + 1];
        ++g.tapBegin[taps_[t].b + 1];
      }
    }
    for (const ClusterLink& c : clusterLinks_)
      for (uint32_t t = c.tapBegin; t < c.tapBegin + c.tapCount; ++t)
        ++g.tapBegin[clusterTaps_[t].receiver + 1];
    for (size_t e = 0; e < n; ++e) {
      g.linkBegin[e + 1] += g.linkBegin[e];
      g.tapBegin[e + 1] += g.tapBegin[e];
    }
    g.linkTerms.resize(g.linkBegin[n]);
    g.tapTerms.resize(g.tapBegin[n]);
    std::vector<uint32_t> linkAt(g.linkBegin.begin(), g.linkBegin.end() - 1);
    std::vector<uint32_t> tapAt(g.tapBegin.begin(), g.tapBegin.end() - 1);
    for (const Link& l : links_) {
      if (l.tapCount == 0) {
        g.linkTerms[linkAt[l.a]++] = {l.b, l.formFactorAB};
        g.linkTerms[linkAt[l.b]++] = {l.a, l.formFactorBA};
        continue;
      }
      // Partial: each clear sample carries its share from the part of one element it ends on to
      // the part of the other (see Tap).
      for (uint32_t t = l.tapBegin; t < l.tapBegin + l.tapCount; ++t) {
        const Tap& tap = taps_[t];
        g.tapTerms[tapAt[tap.a]++] = {tap.fromB, tap.intoA};
        g.tapTerms[tapAt[tap.b]++] = {tap.fromA, tap.intoB};
      }
    }
    // Cluster links: each clear sample from the element it left to the patch it reached.
    for (const ClusterLink& c : clusterLinks_)
      for (uint32_t t = c.tapBegin; t < c.tapBegin + c.tapCount; ++t)
        g.tapTerms[tapAt[clusterTaps_[t].receiver]++] = {clusterTaps_[t].source,
                                                         clusterTaps_[t].coefficient};
    return g;
  }

  /// The largest change and the largest radiosity of a sweep (any channel).
  struct SweepChange {
    double change = 0, radiosity = 0;
  };

  /// Jacobi iteration of gather + push-pull until the largest change is below tolerance. Both
  /// halves run in parallel (gather per receiving element, push-pull per patch) and add in a
  /// fixed order; the maxima are exact, so the solution does not depend on the thread count.
  bool solve(RefinementStats& round) {
    const auto t0 = Clock::now();
    refreshTaps();
    liftConcentratedTaps(round);
    const GatherLists lists = gatherLists();
    const size_t patches = tree_.patchCount();
    std::vector<SweepChange> changes(patches);
    bool converged = false;
    int sweep = 0;
    while (sweep < options_.maxSweeps) {
      ++sweep;
      parallelForEach(tree_.size(), [&](size_t e) {
        Rgb g{};
        for (uint32_t t = lists.linkBegin[e]; t < lists.linkBegin[e + 1]; ++t)
          g += lists.linkTerms[t].second * radiosity_[lists.linkTerms[t].first];
        for (uint32_t t = lists.tapBegin[e]; t < lists.tapBegin[e + 1]; ++t)
          g += static_cast<double>(lists.tapTerms[t].second) * radiosity_[lists.tapTerms[t].first];
        gathered_[e] = g;
      });
      parallelForEach(patches, [&](size_t p) {
        changes[p] = {};
        pushPull(static_cast<uint32_t>(p), Rgb{}, changes[p]);
      });
      SweepChange largest;
      for (const SweepChange& c : changes) {
        largest.change = std::max(largest.change, c.change);
        largest.radiosity = std::max(largest.radiosity, c.radiosity);
      }
      if (largest.change <= options_.tolerance * largest.radiosity) {
        converged = true;
        break;
      }
    }
    round.sweeps = sweep;
    round.solveSeconds = secondsSince(t0);
    return converged;
  }

  /// Push the irradiance gathered at ancestors (`down`) to the leaves, where B = E + ρ · total;
  /// pull the area-weighted mean back up. Returns the element's new radiosity; adds its change to
  /// `sweep`. Writes only e's subtree: patches run in parallel.
  Rgb pushPull(uint32_t e, const Rgb& down, SweepChange& sweep) {
    const Element& el = tree_[e];
    const Rgb total = down + gathered_[e];
    Rgb b;
    double brightest = 0;
    if (el.isLeaf()) {
      b = emission_[el.patch] + reflectance_[el.patch] * total;
      brightest = maxChannel(b);
    } else {
      double area = 0;
      for (uint32_t c = el.firstChild; c < el.firstChild + el.childCount; ++c) {
        b += tree_[c].area * pushPull(c, total, sweep);
        area += tree_[c].area;
        brightest = std::max(brightest, brightest_[c]);
      }
      b = (1.0 / area) * b;
    }
    brightest_[e] = brightest;
    const Rgb old = radiosity_[e];
    sweep.change = std::max(
        {sweep.change, std::abs(b.r - old.r), std::abs(b.g - old.g), std::abs(b.b - old.b)});
    sweep.radiosity = std::max(sweep.radiosity, maxChannel(b));
    radiosity_[e] = b;
    return b;
  }

  void finishRound(RefinementStats& round, Clock::time_point t0) {
    round.refineSeconds = secondsSince(t0);
    round.elements = tree_.size();
    round.leaves = tree_.leafCount();
    round.clusterLinks = clusterLinks_.size();
    round.clusterTaps = clusterTaps_.size();
    for (const Link& l : links_) {
      if (l.status == VisibilityStatus::Visible)
        ++round.links.visible;
      else if (l.status == VisibilityStatus::Partial)
        ++round.links.partial;
      else
        ++round.links.invisible;
    }
  }

  void report(const RefinementStats& r) const {
    if (!options_.progress) return;
    options_.progress(
        fmt::format("radiosity round {}: {} links refined, {} links (V {} / P {} / I {}), created "
                    "V {} P {} I {}, "
                    "{} cluster links, {} elements, {} rays, refine {:.2f} s, solve {} sweeps "
                    "{:.2f} s",
                    r.round, r.linksRefined, r.links.total(), r.links.visible, r.links.partial,
                    r.links.invisible, r.created.visible, r.created.partial, r.created.invisible,
                    r.clusterLinks, r.elements, r.rays, r.refineSeconds, r.sweeps, r.solveSeconds));
  }

  const Scene& scene_;
  LinkVisibility& visibility_;
  const RadiosityOptions& options_;
  Tolerance tol_;
  ElementTree tree_;
  std::vector<Link> links_;
  std::vector<Tap> taps_;  ///< of the Partial links (Link::tapBegin)
  /// How far below a source its pieces are weighed (computeSourceWeights): up to 16 pieces.
  static constexpr uint32_t kSourcePieceDepth = 2;
  struct SourcePiece {
    uint32_t element = 0;  ///< a piece; in a group's first entry, the group's size
    float weight = 0;
  };
  std::vector<double> leafSpread_;         ///< per element, leaves only (updateLeafSpread)
  std::vector<SourcePiece> sourcePieces_;  ///< computeSourceWeights' (Link::sourcePiecesOfA/B)
  std::vector<double> deviationPool_;  ///< computeChildDeviations' values (Link::deviationsAtA/B)
  /// Per element, the stamp of the last change to its links within a round (a link at it added
  /// or replaced); see ConsistencyPass. Elements made later start at the stamp of their making.
  std::vector<uint32_t> changedAt_;
  uint32_t stamp_ = 1;
  ConsistencyPass receiverPass_, sourcePass_;
  std::vector<Rgb> emission_, reflectance_;  ///< per patch
  std::vector<Rgb> radiosity_, gathered_;    ///< per element
  std::vector<double> brightest_;  ///< per element: the largest leaf radiosity below (any channel)
  double minArea_ = 0, threshold_ = 0;
  std::vector<double> thresholdScale_;  ///< per patch: its threshold over threshold_
  /// Per cluster (once clustered): the smallest thresholdScale_ of its patches.
  std::vector<double> clusterThresholdScale_;
  RadiosityStats stats_;
  RefinementStats* current_ = nullptr;
  /// Clustering (RadiosityOptions::clusterSamples): the tree, the oracle's candidate pairs, the
  /// links between clusters with their samples, and per cluster its largest leaf radiosity.
  std::optional<ClusterTree> clusters_;
  std::optional<CandidatePairs> candidates_;
  std::vector<ClusterLink> clusterLinks_;
  std::vector<ClusterTap> clusterTaps_;
  std::vector<double> clusterBright_;
};

}  // namespace

RadiosityResult solveRadiosity(const Scene& scene, LinkVisibility& visibility,
                               const RadiosityOptions& options) {
  const int threads =
      options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  // Every parallel loop of the solver and of the oracle's estimateAll runs in this arena.
  tbb::task_arena arena(threads);
  std::optional<RadiosityResult> result;
  arena.execute([&] {
    Solver solver(scene, visibility, options);
    result.emplace(solver.run());
  });
  result->stats.threads = threads;
  return std::move(*result);
}

}  // namespace gv
