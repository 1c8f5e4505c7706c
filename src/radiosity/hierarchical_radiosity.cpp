// Hierarchical radiosity: initial links, BF refinement, Jacobi gather with push-pull. HSA91 §4,
// paper §6 and §7.4 (Table 1 statistics per refinement round).
#include "radiosity/hierarchical_radiosity.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

#include "radiosity/polygon_sampling.h"
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
  return std::max({x.r, x.g, x.b});
}

/// The rule of three: N agreeing samples bound the missed fraction by ~3 / N (95 %).
constexpr double kSampleBound = 3.0;

/// Where a Partial link's light passes: one clear sample of its visibility, as the elements its
/// two ends lie in (the deepest that existed when the link was made) and the form factors that
/// carry the sample's share of the link between them. A link hands its receiver the source's
/// mean radiosity, spread evenly; when part of the path is blocked, the part of the source in
/// view is often not its average and the lit part of the receiver not all of it (a ceiling
/// patch spanning a lit room and a dark corridor sees only the room's floor). Gathering through
/// the taps keeps that correlation: a one-room office was 4.2 % dark against light tracing
/// through the means, 1.6 % through taps. Shares sum to the link's visibility fraction, so each
/// element's total gather (its mean) is unchanged; only where it lands and from where moves.
struct Tap {
  uint32_t a = 0, b = 0;  ///< elements at the sample's ends (descendants of the link's a and b)
  float intoA = 0;        ///< tap.a gathers intoA · B(tap.b): F_ab · share · A_a / A_tap.a
  float intoB = 0;        ///< tap.b gathers intoB · B(tap.a)
};

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
    double area = 0;
    for (size_t k = 0; k < scene.patches.size(); ++k) {
      area += tree_[static_cast<uint32_t>(k)].area;
      stats_.emittedPower += tree_[static_cast<uint32_t>(k)].area * maxChannel(emission_[k]);
    }
    minArea_ = options.minArea * area;
    threshold_ = options.epsilon * stats_.emittedPower;
    stats_.visibility = std::string(visibility.name());
    stats_.patches = scene.patches.size();
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
    stats_.converged = refinedNothing && solved;
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
  void makeInitialLinks() {
    const double eps = tol_.length();
    visibility_.forEachCandidatePair([&](uint32_t a, uint32_t b, TubeId tube) {
      ++stats_.candidatePairs;
      if (!canFace(tree_[a].polygon, tree_[b].polygon, eps)) return;
      ++stats_.facingPairs;
      if (std::optional<Link> link = makeLink(a, b, tube)) links_.push_back(*link);
    });
  }

  /// Form factor (exact, unoccluded) times the oracle's visibility; nullopt when no light passes.
  std::optional<Link> makeLink(uint32_t a, uint32_t b, TubeId parentTube) {
    const Element& ea = tree_[a];
    const Element& eb = tree_[b];
    if (!canFace(ea.polygon, eb.polygon, tol_.length())) return std::nullopt;
    ++current_->interactions;
    // Integrate over the smaller element: the quadrature's accuracy depends on the integration
    // domain's size relative to the distance; reciprocity gives the other direction.
    double fab, variationA, variationB;
    if (eb.area < ea.area) {
      const FormFactorEstimate e =
          formFactorEstimate(eb.polygon, ea.polygon, tol_, options_.formFactor);
      fab = e.ab * eb.area / ea.area;
      variationA = e.variationB;
      variationB = e.variationA;
    } else {
      const FormFactorEstimate e =
          formFactorEstimate(ea.polygon, eb.polygon, tol_, options_.formFactor);
      fab = e.ab;
      variationA = e.variationA;
      variationB = e.variationB;
    }
    if (!(fab > 0)) return std::nullopt;
    const VisibilityEstimate v =
        visibility_.estimate(ea, eb, parentTube, mixSeed(options_.seed, a, b));
    current_->rays += v.raysCast;
    switch (v.status) {
      case VisibilityStatus::Invisible:
        ++current_->created.invisible;
        // Proven (no rays needed): no light passes. Sampled: light narrower than the samples
        // may pass; the link is kept, carrying nothing, so that refinement can look again
        // (dropping it would bias the solution dark, by p (1 - p)^N per link).
        if (v.raysCast == 0) return std::nullopt;
        break;
      case VisibilityStatus::Partial:
        ++current_->created.partial;
        break;
      case VisibilityStatus::Visible:
        ++current_->created.visible;
        break;
    }
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
    link.variationA = variationA;
    link.variationB = variationB;
    link.visibility = static_cast<float>(v.fraction);
    link.formFactorAB = fab * v.fraction;
    link.formFactorBA = fab * ea.area / eb.area * v.fraction;
    link.status = v.status;
    link.tube = v.tube;
    link.samples = static_cast<uint32_t>(std::min<uint64_t>(v.raysCast, UINT32_MAX));
    if (v.status == VisibilityStatus::Partial && !v.clearSamples.empty()) {
      link.tapBegin = static_cast<uint32_t>(taps_.size());
      link.tapCount = static_cast<uint32_t>(v.clearSamples.size());
      const double fba = fab * ea.area / eb.area;
      for (const ClearSample& c : v.clearSamples) {
        const uint32_t ta = tree_.deepestContaining(a, c.from);
        const uint32_t tb = tree_.deepestContaining(b, c.to);
        taps_.push_back({ta, tb, static_cast<float>(fab * c.weight * ea.area / tree_[ta].area),
                         static_cast<float>(fba * c.weight * eb.area / tree_[tb].area)});
      }
    }
    return link;
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
    // A sampled visibility of 0 or 1 is uncertain: after N samples that all agree, the fraction
    // missed can still be up to ~3 / N (the "rule of three", a 95 % bound). Without this term,
    // links that happened to sample all clear or all blocked stop refining, and the solution is
    // biased towards whichever extreme is more common (a desk under a ceiling patch that spans
    // every room: 16 rays all land in other rooms, and the desk never sees its own ceiling).
    const double uncertain =
        l.samples == 0 ? 0.0 : std::min(1.0, kSampleBound / static_cast<double>(l.samples));
    const double ba = l.unoccludedAB, bb = l.unoccludedAB * ea.area / eb.area;
    double boundA = ba, boundB = bb;
    if (l.status == VisibilityStatus::Visible) {
      boundA = std::max(l.variationA, uncertain * ba);
      boundB = std::max(l.variationB, uncertain * bb);
    } else if (l.status == VisibilityStatus::Invisible) {
      boundA = uncertain * ba;
      boundB = uncertain * bb;
    }
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
    return e;
  }

  /// How much an element's radiosity varies: the range over its children; 0 for a leaf (the
  /// solver knows nothing finer).
  double radiosityRange(uint32_t e) const {
    const Element& el = tree_[e];
    if (el.isLeaf()) return 0.0;
    double lo = INFINITY, hi = -INFINITY;
    for (uint32_t c = el.firstChild; c < el.firstChild + el.childCount; ++c) {
      lo = std::min(lo, maxChannel(radiosity_[c]));
      hi = std::max(hi, maxChannel(radiosity_[c]));
    }
    return hi - lo;
  }

  bool canSplit(uint32_t e) const { return tree_[e].area >= minArea_; }

  /// HSA91's Refine, iterated with an explicit stack: a link whose error exceeds the threshold is
  /// replaced by links from the children of one of its elements to the other; those are examined
  /// in turn (with the parent's radiosity, which children inherit). Which element: for a Visible
  /// link the receiver of the worse direction, since only cutting the receiver narrows the spread
  /// of the form factor across it; for a Partial link the larger one (HSA91's rule), which
  /// narrows the visibility sample most.
  void refineLinks(RefinementStats& round) {
    std::vector<Link> pending = std::move(links_);
    links_.clear();
    refinePending(pending, round, true);
    while (pushInconsistentLinks(pending, round)) refinePending(pending, round, false);
  }

  /// Splits `l` by its element `split` (which has children) and queues the children's links.
  void replaceBy(const Link& l, uint32_t split, std::vector<Link>& pending,
                 RefinementStats& round) {
    ++round.linksRefined;
    const Element& parent = tree_[split];
    const uint32_t first = parent.firstChild, count = parent.childCount;
    for (uint32_t c = first; c < first + count; ++c) {
      std::optional<Link> child =
          split == l.a ? makeLink(c, l.b, l.tube) : makeLink(l.a, c, l.tube);
      if (child) pending.push_back(*child);
    }
  }

  /// `report`: progress goes to refineProgress (the round's main pass; the consistency passes
  /// after it are not reported).
  void refinePending(std::vector<Link>& pending, RefinementStats& round, bool report) {
    // Children go on top of the stack, so the round's own links are its bottom `originals`.
    const size_t total = pending.size();
    size_t originals = total;
    while (!pending.empty()) {
      if (pending.size() == originals) {
        --originals;
        const size_t done = total - originals;
        if (report && options_.refineProgress && (done % 256 == 0 || done == total))
          options_.refineProgress(done, total);
      }
      const Link l = pending.back();
      pending.pop_back();
      const LinkError error = linkError(l);
      if (error.worst() <= threshold_) {
        links_.push_back(l);
        continue;
      }
      bool preferA = l.status == VisibilityStatus::Visible ? error.intoA >= error.intoB
                                                           : tree_[l.a].area >= tree_[l.b].area;
      // A source term dominating: cut that source (b for clipA / sourceA, a for B's).
      const double sourceOfA = error.clipA + error.sourceA, sourceOfB = error.clipB + error.sourceB;
      if (std::max(sourceOfA, sourceOfB) > std::max(error.intoA, error.intoB))
        preferA = sourceOfB >= sourceOfA;
      uint32_t split = preferA ? l.a : l.b;
      if (!canSplit(split)) split = preferA ? l.b : l.a;
      if (!canSplit(split) || !subdivide(split)) {
        links_.push_back(l);
        continue;
      }
      replaceBy(l, split, pending, round);
    }
  }

  /// Receiver-side consistency (RadiosityOptions::relativeEpsilon). The links ending at a
  /// subdivided element hand each child the element's mean form factor; the child's own mean
  /// differs. Per child, the signed sum of those differences (estimated by the point form factor
  /// at the child's centroid), weighted by ρ B_src visibility, as a fraction of the element's
  /// radiosity, must stay within relativeEpsilon; otherwise the links adding most to the worst
  /// child's error are refined into the existing children until it fits. Errors of opposite
  /// sign cancel (a child nearer one source is farther from another), so only coherent ones (a
  /// corner child under coarse links to far walls) cost links. Moves the links to `pending`;
  /// returns whether any moved.
  bool pushInconsistentLinks(std::vector<Link>& pending, RefinementStats& round) {
    std::vector<std::vector<uint32_t>> ends(tree_.size());
    for (uint32_t i = 0; i < links_.size(); ++i) {
      const Link& l = links_[i];
      if (!tree_[l.a].isLeaf()) ends[l.a].push_back(i);
      if (!tree_[l.b].isLeaf()) ends[l.b].push_back(i);
    }
    std::vector<uint32_t> splitBy(links_.size(), kNoElement);
    bool any = false;
    std::vector<double> contribution, deviation;
    std::vector<uint32_t> order;
    for (uint32_t e = 0; e < ends.size(); ++e) {
      const std::vector<uint32_t>& list = ends[e];
      const double be = maxChannel(radiosity_[e]);
      if (list.empty() || !(be > 0)) continue;
      const Element& el = tree_[e];
      const uint32_t first = el.firstChild, k = el.childCount;
      const double budget = options_.relativeEpsilon;
      contribution.assign(list.size() * k, 0.0);
      deviation.assign(k, 0.0);
      for (size_t j = 0; j < list.size(); ++j) {
        Link& l = links_[list[j]];
        const bool atA = l.a == e;
        const uint32_t other = atA ? l.b : l.a;
        const double weight =
            maxChannel(reflectance_[el.patch] * radiosity_[other]) * l.visibility / be;
        const double* offMean = childDeviations(l, e);
        for (uint32_t c = 0; c < k; ++c)
          deviation[c] += contribution[j * k + c] = weight * offMean[c];
      }
      for (uint32_t pass = 0; pass <= k; ++pass) {
        uint32_t worst = 0;
        for (uint32_t c = 1; c < k; ++c)
          if (std::abs(deviation[c]) > std::abs(deviation[worst])) worst = c;
        if (std::abs(deviation[worst]) <= budget) break;
        const double sign = deviation[worst] > 0 ? 1.0 : -1.0;
        order.clear();
        for (uint32_t j = 0; j < list.size(); ++j)
          if (splitBy[list[j]] != e && sign * contribution[j * k + worst] > 0) order.push_back(j);
        std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) {
          const double cx = sign * contribution[x * k + worst],
                       cy = sign * contribution[y * k + worst];
          return cx != cy ? cx > cy : x < y;
        });
        for (uint32_t j : order) {
          if (std::abs(deviation[worst]) <= budget) break;
          for (uint32_t c = 0; c < k; ++c) deviation[c] -= contribution[j * k + c];
          if (splitBy[list[j]] == kNoElement) {
            splitBy[list[j]] = e;
            any = true;
          }
        }
      }
    }
    if (!any) return false;
    std::vector<Link> kept;
    kept.reserve(links_.size());
    for (uint32_t i = 0; i < links_.size(); ++i) {
      if (splitBy[i] == kNoElement)
        kept.push_back(links_[i]);
      else
        replaceBy(links_[i], splitBy[i], pending, round);
    }
    links_ = std::move(kept);
    return true;
  }

  /// Per child c of `e` (an end of `l`, with children): the link's mean form factor into e minus
  /// the point form factor at c's centroid. Geometry only, so computed once per link end and
  /// kept (Link::deviationsAtA/B): the consistency passes revisit the same links every pass and
  /// every round.
  const double* childDeviations(Link& l, uint32_t e) {
    const bool atA = l.a == e;
    uint32_t& at = atA ? l.deviationsAtA : l.deviationsAtB;
    if (at == UINT32_MAX) {
      at = static_cast<uint32_t>(deviationPool_.size());
      const uint32_t other = atA ? l.b : l.a;
      const Element& el = tree_[e];
      const double mean = atA ? l.unoccludedAB : l.unoccludedAB * tree_[l.a].area / tree_[l.b].area;
      for (uint32_t c = el.firstChild; c < el.firstChild + el.childCount; ++c)
        deviationPool_.push_back(mean - pointFormFactorToFront(tree_[c].polygon.centroid(),
                                                               el.polygon.plane,
                                                               tree_[other].polygon, tol_));
    }
    return deviationPool_.data() + at;
  }

  /// Drops the taps of links that refinement replaced (they are only appended).
  void compactTaps() {
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
    }
    return true;
  }

  /// Jacobi iteration of gather + push-pull until the largest change is below tolerance.
  bool solve(RefinementStats& round) {
    const auto t0 = Clock::now();
    bool converged = false;
    int sweep = 0;
    while (sweep < options_.maxSweeps) {
      ++sweep;
      std::fill(gathered_.begin(), gathered_.end(), Rgb{});
      for (const Link& l : links_) {
        if (l.tapCount == 0) {
          gathered_[l.a] += l.formFactorAB * radiosity_[l.b];
          gathered_[l.b] += l.formFactorBA * radiosity_[l.a];
          continue;
        }
        // Partial: each clear sample carries its share from the part of one element it ends
        // on to the part of the other (see Tap).
        for (uint32_t t = l.tapBegin; t < l.tapBegin + l.tapCount; ++t) {
          const Tap& tap = taps_[t];
          gathered_[tap.a] += static_cast<double>(tap.intoA) * radiosity_[tap.b];
          gathered_[tap.b] += static_cast<double>(tap.intoB) * radiosity_[tap.a];
        }
      }
      maxChange_ = 0;
      maxRadiosity_ = 0;
      for (uint32_t p = 0; p < tree_.patchCount(); ++p) pushPull(p, Rgb{});
      if (maxChange_ <= options_.tolerance * maxRadiosity_) {
        converged = true;
        break;
      }
    }
    round.sweeps = sweep;
    round.solveSeconds = secondsSince(t0);
    return converged;
  }

  /// Push the irradiance gathered at ancestors (`down`) to the leaves, where B = E + ρ · total;
  /// pull the area-weighted mean back up. Returns the element's new radiosity.
  Rgb pushPull(uint32_t e, const Rgb& down) {
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
        b += tree_[c].area * pushPull(c, total);
        area += tree_[c].area;
        brightest = std::max(brightest, brightest_[c]);
      }
      b = (1.0 / area) * b;
    }
    brightest_[e] = brightest;
    const Rgb old = radiosity_[e];
    maxChange_ =
        std::max({maxChange_, std::abs(b.r - old.r), std::abs(b.g - old.g), std::abs(b.b - old.b)});
    maxRadiosity_ = std::max(maxRadiosity_, maxChannel(b));
    radiosity_[e] = b;
    return b;
  }

  void finishRound(RefinementStats& round, Clock::time_point t0) {
    round.refineSeconds = secondsSince(t0);
    round.elements = tree_.size();
    round.leaves = tree_.leafCount();
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
                    "{} elements, {} rays, refine {:.2f} s, solve {} sweeps {:.2f} s",
                    r.round, r.linksRefined, r.links.total(), r.links.visible, r.links.partial,
                    r.links.invisible, r.created.visible, r.created.partial, r.created.invisible,
                    r.elements, r.rays, r.refineSeconds, r.sweeps, r.solveSeconds));
  }

  const Scene& scene_;
  LinkVisibility& visibility_;
  const RadiosityOptions& options_;
  Tolerance tol_;
  ElementTree tree_;
  std::vector<Link> links_;
  std::vector<Tap> taps_;                    ///< of the Partial links (Link::tapBegin)
  std::vector<double> deviationPool_;        ///< childDeviations' values (Link::deviationsAtA/B)
  std::vector<Rgb> emission_, reflectance_;  ///< per patch
  std::vector<Rgb> radiosity_, gathered_;    ///< per element
  std::vector<double> brightest_;  ///< per element: the largest leaf radiosity below (any channel)
  double minArea_ = 0, threshold_ = 0;
  double maxChange_ = 0, maxRadiosity_ = 0;
  RadiosityStats stats_;
  RefinementStats* current_ = nullptr;
};

}  // namespace

RadiosityResult solveRadiosity(const Scene& scene, LinkVisibility& visibility,
                               const RadiosityOptions& options) {
  Solver solver(scene, visibility, options);
  return solver.run();
}

}  // namespace gv
