// Radiosity output files: radiosity.txt, stats.json (paper Table 1), elements.ply.
#include "radiosity/radiosity_io.h"

#include <fmt/core.h>
#include <fmt/os.h>

#include <algorithm>
#include <cmath>

#include "radiosity/element_mesh.h"
#include "util/check.h"
#include "util/input_error.h"

namespace gv {
namespace {

/// Output gamma of the PLY colours (a plain power curve, close to sRGB's).
constexpr double kDisplayGamma = 2.2;
/// Percentile of leaf radiosity (by area) that maps to white.
constexpr double kWhitePercentile = 0.99;

double percent(size_t part, size_t whole) {
  return whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

nlohmann::json countsJson(const LinkCounts& c) {
  const size_t total = c.total();
  return {{"visible", c.visible},
          {"partial", c.partial},
          {"invisible", c.invisible},
          {"total", total},
          {"visible_percent", percent(c.visible, total)},
          {"partial_percent", percent(c.partial, total)},
          {"invisible_percent", percent(c.invisible, total)}};
}

double maxChannel(const Rgb& x) {
  return x.maxChannel();
}

}  // namespace

void writeRadiosityTxt(const RadiosityResult& result, const std::string& path) {
  writePatchRgbTxt(result.patchRadiosity,
                   fmt::format("patch R G B = area-weighted mean radiosity (linear, same units as "
                               "Ke)\n# visibility {}, {} patches, converged {}",
                               result.stats.visibility, result.patchRadiosity.size(),
                               result.stats.converged ? "yes" : "no"),
                   path);
}

void writePatchRgbTxt(const std::vector<Rgb>& values, const std::string& header,
                      const std::string& path) {
  try {
    auto out = fmt::output_file(path);
    out.print("# globalvis radiosity: one line per patch of patches.obj, in face order\n");
    out.print("# {}\n", header);
    for (size_t p = 0; p < values.size(); ++p) {
      const Rgb& b = values[p];
      out.print("{} {:.9g} {:.9g} {:.9g}\n", p, b.r, b.g, b.b);
    }
  } catch (const std::exception& e) {
    throw InputError(path, 0, std::string("cannot write: ") + e.what());
  }
}

nlohmann::json radiosityStatsJson(const RadiosityStats& stats, const RadiosityOptions& options,
                                  int raysPerLink) {
  nlohmann::json rounds = nlohmann::json::array();
  for (const RefinementStats& r : stats.rounds) {
    rounds.push_back({{"round", r.round},
                      {"links_created", countsJson(r.created)},
                      {"links", countsJson(r.links)},
                      {"links_refined", r.linksRefined},
                      {"consistency_passes", r.consistencyPasses},
                      {"cluster_links", r.clusterLinks},
                      {"cluster_taps", r.clusterTaps},
                      {"cluster_pairs_invisible", r.clusterPairsInvisible},
                      {"elements", r.elements},
                      {"leaves", r.leaves},
                      {"interactions", r.interactions},
                      {"rays", r.rays},
                      {"refine_seconds", r.refineSeconds},
                      {"solve_sweeps", r.sweeps},
                      {"solve_seconds", r.solveSeconds},
                      {"taps_lifted", r.tapsLifted}});
  }
  return {{"visibility", stats.visibility},
          {"threads", stats.threads},
          {"options",
           {{"rays_per_link", raysPerLink},
            {"epsilon", options.epsilon},
            {"form_factor_tolerance", options.formFactor.relativeTolerance},
            {"relative_epsilon", options.relativeEpsilon},
            {"source_epsilon", options.sourceEpsilon},
            {"min_area", options.minArea},
            {"tolerance", options.tolerance},
            {"max_refinements", options.maxRefinements},
            {"seed", options.seed},
            {"max_links", options.maxLinks},
            {"cluster_samples", options.clusterSamples}}},
          {"clustered", stats.clustered},
          {"patches", stats.patches},
          {"candidate_pairs", stats.candidatePairs},
          {"facing_pairs", stats.facingPairs},
          {"emitted_power", stats.emittedPower},
          {"rounds", rounds},
          {"totals",
           {{"rays", stats.rays},
            {"interactions", stats.interactions},
            {"links", stats.rounds.empty() ? 0 : stats.rounds.back().links.total()},
            {"cluster_links", stats.rounds.empty() ? 0 : stats.rounds.back().clusterLinks},
            {"elements", stats.rounds.empty() ? 0 : stats.rounds.back().elements},
            {"seconds", stats.seconds},
            {"converged", stats.converged},
            {"link_budget_reached", stats.linkBudgetReached}}}};
}

void writeElementsPly(const RadiosityResult& result, const std::string& path, double white) {
  const ElementTree& tree = result.elements;
  CHECK_MSG(result.elementRadiosity.size() == tree.size(), "{} element values for {} elements",
            result.elementRadiosity.size(), tree.size());
  if (!(white > 0)) {
    std::vector<std::pair<double, double>> byValue;  // (radiosity, area) of leaves
    double area = 0;
    for (uint32_t e = 0; e < tree.size(); ++e) {
      if (!tree[e].isLeaf()) continue;
      byValue.emplace_back(maxChannel(result.elementRadiosity[e]), tree[e].area);
      area += tree[e].area;
    }
    std::sort(byValue.begin(), byValue.end());
    double seen = 0;
    for (const auto& [value, a] : byValue) {
      seen += a;
      white = value;
      if (seen >= kWhitePercentile * area) break;
    }
    if (!(white > 0)) white = 1;
  }
  const ElementMesh mesh = buildElementMesh(result);
  auto tone = [white](double x) {
    const double v = std::pow(std::clamp(x / white, 0.0, 1.0), 1.0 / kDisplayGamma);
    return static_cast<int>(std::lround(255.0 * v));
  };
  try {
    auto out = fmt::output_file(path);
    out.print("ply\nformat ascii 1.0\n");
    out.print(
        "comment globalvis radiosity: leaf elements; colours = radiosity / {:.6g}, gamma "
        "1/{}\n",
        white, kDisplayGamma);
    out.print("element vertex {}\nproperty double x\nproperty double y\nproperty double z\n",
              mesh.positions.size());
    out.print("property uchar red\nproperty uchar green\nproperty uchar blue\n");
    out.print(
        "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n");
    out.print("element face {}\nproperty list uchar int vertex_indices\nend_header\n",
              mesh.faces.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const Vec3& p = mesh.positions[v];
      const Rgb& c = mesh.vertexRadiosity[v];
      out.print("{:.9g} {:.9g} {:.9g} {} {} {} {:.6g} {:.6g} {:.6g}\n", p.x, p.y, p.z, tone(c.r),
                tone(c.g), tone(c.b), c.r, c.g, c.b);
    }
    for (const std::vector<uint32_t>& f : mesh.faces) {
      out.print("{}", f.size());
      for (uint32_t i : f) out.print(" {}", i);
      out.print("\n");
    }
  } catch (const std::exception& e) {
    throw InputError(path, 0, std::string("cannot write: ") + e.what());
  }
}

}  // namespace gv
