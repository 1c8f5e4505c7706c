// Hierarchical radiosity: initial links, BF refinement, Jacobi gather with push-pull. HSA91 §4,
// paper §6 and §7.4 (Table 1 statistics per refinement round).
#include "radiosity/hierarchical_radiosity.h"
#include "util/timing.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

#include "radiosity/polygon_sampling.h"

namespace gv {
namespace {

Rgb operator+(const Rgb& x, const Rgb& y) { return {x.r + y.r, x.g + y.g, x.b + y.b}; }
Rgb operator*(const Rgb& x, const Rgb& y) { return {x.r * y.r, x.g * y.g, x.b * y.b}; }
Rgb operator*(double s, const Rgb& x) { return {s * x.r, s * x.g, s * x.b}; }
Rgb& operator+=(Rgb& x, const Rgb& y) { return x = x + y; }
double maxChannel(const Rgb& x) { return std::max({x.r, x.g, x.b}); }

class Solver {
 public:
  Solver(const Scene& scene, LinkVisibility& visibility, const RadiosityOptions& options)
      : scene_(scene), visibility_(visibility), options_(options), tol_(scene.tolerance()),
        tree_(scene) {
    emission_.reserve(scene.patches.size());
    reflectance_.reserve(scene.patches.size());
    for (const Patch& p : scene.patches) {
      const Material& m = scene.materials.at(p.material);
      emission_.push_back(m.emission);
      reflectance_.push_back(m.reflectance);
    }
    radiosity_ = emission_;
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
      const FormFactorEstimate e = formFactorEstimate(eb.polygon, ea.polygon, tol_, options_.formFactor);
      fab = e.ab * eb.area / ea.area;
      variationA = e.variationB;
      variationB = e.variationA;
    } else {
      const FormFactorEstimate e = formFactorEstimate(ea.polygon, eb.polygon, tol_, options_.formFactor);
      fab = e.ab;
      variationA = e.variationA;
      variationB = e.variationB;
    }
    if (!(fab > 0)) return std::nullopt;
    const VisibilityEstimate v = visibility_.estimate(ea, eb, parentTube, mixSeed(options_.seed, a, b));
    current_->rays += v.raysCast;
    switch (v.status) {
      case VisibilityStatus::Invisible: ++current_->created.invisible; return std::nullopt;
      case VisibilityStatus::Partial: ++current_->created.partial; break;
      case VisibilityStatus::Visible: ++current_->created.visible; break;
    }
    Link link;
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
    return link;
  }

  /// The BF error estimate (see RadiosityOptions::epsilon): reflected power the link may get
  /// wrong in either direction. Partial links count their whole unoccluded form factor: their
  /// visibility is a sample, and where it varies across the receiver is unknown.
  struct LinkError {
    double intoA = 0, intoB = 0;
    double worst() const { return std::max(intoA, intoB); }
  };
  LinkError linkError(const Link& l) const {
    const Element& ea = tree_[l.a];
    const Element& eb = tree_[l.b];
    const bool visible = l.status == VisibilityStatus::Visible;
    const double boundA = visible ? l.variationA : l.unoccludedAB;
    const double boundB = visible ? l.variationB : l.unoccludedAB * ea.area / eb.area;
    return {maxChannel(reflectance_[ea.patch] * radiosity_[l.b]) * ea.area * boundA,
            maxChannel(reflectance_[eb.patch] * radiosity_[l.a]) * eb.area * boundB};
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
    // Children go on top of the stack, so the round's own links are its bottom `originals`.
    const size_t total = pending.size();
    size_t originals = total;
    while (!pending.empty()) {
      if (pending.size() == originals) {
        --originals;
        const size_t done = total - originals;
        if (options_.refineProgress && (done % 256 == 0 || done == total))
          options_.refineProgress(done, total);
      }
      const Link l = pending.back();
      pending.pop_back();
      const LinkError error = linkError(l);
      if (error.worst() <= threshold_) {
        links_.push_back(l);
        continue;
      }
      const bool preferA = l.status == VisibilityStatus::Visible
                               ? error.intoA >= error.intoB
                               : tree_[l.a].area >= tree_[l.b].area;
      uint32_t split = preferA ? l.a : l.b;
      if (!canSplit(split)) split = preferA ? l.b : l.a;
      if (!canSplit(split) || !subdivide(split)) {
        links_.push_back(l);
        continue;
      }
      ++round.linksRefined;
      const Element& parent = tree_[split];
      const uint32_t first = parent.firstChild, count = parent.childCount;
      for (uint32_t c = first; c < first + count; ++c) {
        std::optional<Link> child = split == l.a ? makeLink(c, l.b, l.tube) : makeLink(l.a, c, l.tube);
        if (child) pending.push_back(*child);
      }
    }
  }

  bool subdivide(uint32_t e) {
    const bool had = !tree_[e].isLeaf();
    if (!tree_.subdivide(e)) return false;
    if (!had) {
      // New elements start with their parent's radiosity (what push-pull would give them).
      const Rgb inherited = radiosity_[e];
      radiosity_.resize(tree_.size(), inherited);
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
        gathered_[l.a] += l.formFactorAB * radiosity_[l.b];
        gathered_[l.b] += l.formFactorBA * radiosity_[l.a];
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
    if (el.isLeaf()) {
      b = emission_[el.patch] + reflectance_[el.patch] * total;
    } else {
      double area = 0;
      for (uint32_t c = el.firstChild; c < el.firstChild + el.childCount; ++c) {
        b += tree_[c].area * pushPull(c, total);
        area += tree_[c].area;
      }
      b = (1.0 / area) * b;
    }
    const Rgb old = radiosity_[e];
    maxChange_ = std::max({maxChange_, std::abs(b.r - old.r), std::abs(b.g - old.g),
                           std::abs(b.b - old.b)});
    maxRadiosity_ = std::max(maxRadiosity_, maxChannel(b));
    radiosity_[e] = b;
    return b;
  }

  void finishRound(RefinementStats& round, Clock::time_point t0) {
    round.refineSeconds = secondsSince(t0);
    round.elements = tree_.size();
    round.leaves = tree_.leafCount();
    for (const Link& l : links_) {
      if (l.status == VisibilityStatus::Visible) ++round.links.visible;
      else ++round.links.partial;
    }
  }

  void report(const RefinementStats& r) const {
    if (!options_.progress) return;
    options_.progress(fmt::format(
        "radiosity round {}: {} links refined, {} links (V {} / P {}), created V {} P {} I {}, "
        "{} elements, {} rays, refine {:.2f} s, solve {} sweeps {:.2f} s",
        r.round, r.linksRefined, r.links.total(), r.links.visible, r.links.partial,
        r.created.visible, r.created.partial, r.created.invisible, r.elements, r.rays,
        r.refineSeconds, r.sweeps, r.solveSeconds));
  }

  const Scene& scene_;
  LinkVisibility& visibility_;
  const RadiosityOptions& options_;
  Tolerance tol_;
  ElementTree tree_;
  std::vector<Link> links_;
  std::vector<Rgb> emission_, reflectance_;  ///< per patch
  std::vector<Rgb> radiosity_, gathered_;    ///< per element
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
