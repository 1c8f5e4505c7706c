// Radiosity output files: radiosity.txt, stats.json (paper Table 1), elements.ply.
#include "radiosity/radiosity_io.h"

#include <fmt/core.h>
#include <fmt/os.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <tuple>

#include "scene/input_error.h"

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

double maxChannel(const Rgb& c) {
  return std::max({c.r, c.g, c.b});
}

}  // namespace

void writeRadiosityTxt(const RadiosityResult& result, const std::string& path) {
  try {
    auto out = fmt::output_file(path);
    out.print("# globalvis radiosity: one line per patch of patches.obj, in face order\n");
    out.print("# patch R G B = area-weighted mean radiosity (linear, same units as Ke)\n");
    out.print("# visibility {}, {} patches, converged {}\n", result.stats.visibility,
              result.patchRadiosity.size(), result.stats.converged ? "yes" : "no");
    for (size_t p = 0; p < result.patchRadiosity.size(); ++p) {
      const Rgb& b = result.patchRadiosity[p];
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
                      {"elements", r.elements},
                      {"leaves", r.leaves},
                      {"interactions", r.interactions},
                      {"rays", r.rays},
                      {"refine_seconds", r.refineSeconds},
                      {"solve_sweeps", r.sweeps},
                      {"solve_seconds", r.solveSeconds}});
  }
  return {{"visibility", stats.visibility},
          {"options",
           {{"rays_per_link", raysPerLink},
            {"epsilon", options.epsilon},
            {"relative_epsilon", options.relativeEpsilon},
            {"min_area", options.minArea},
            {"tolerance", options.tolerance},
            {"max_refinements", options.maxRefinements},
            {"seed", options.seed}}},
          {"patches", stats.patches},
          {"candidate_pairs", stats.candidatePairs},
          {"facing_pairs", stats.facingPairs},
          {"emitted_power", stats.emittedPower},
          {"rounds", rounds},
          {"totals",
           {{"rays", stats.rays},
            {"interactions", stats.interactions},
            {"links", stats.rounds.empty() ? 0 : stats.rounds.back().links.total()},
            {"elements", stats.rounds.empty() ? 0 : stats.rounds.back().elements},
            {"seconds", stats.seconds},
            {"converged", stats.converged}}}};
}

void writeElementsPly(const RadiosityResult& result, const std::string& path, double white) {
  const ElementTree& tree = result.elements;
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
  // Vertices shared within a patch: midpoints are computed identically from the same end points,
  // so equal positions have equal bits.
  using Key = std::tuple<uint32_t, uint64_t, uint64_t, uint64_t>;
  std::map<Key, uint32_t> index;
  struct Vertex {
    Vec3 p;
    Rgb sum;
    double weight = 0;
  };
  std::vector<Vertex> vertices;
  std::vector<std::vector<uint32_t>> faces;
  for (uint32_t e = 0; e < tree.size(); ++e) {
    const Element& el = tree[e];
    if (!el.isLeaf()) continue;
    std::vector<uint32_t> face;
    const Rgb& b = result.elementRadiosity[e];
    for (const Vec3& v : el.polygon.vertices) {
      const Key key{el.patch, std::bit_cast<uint64_t>(v.x), std::bit_cast<uint64_t>(v.y),
                    std::bit_cast<uint64_t>(v.z)};
      auto [it, fresh] = index.try_emplace(key, static_cast<uint32_t>(vertices.size()));
      if (fresh) vertices.push_back({v, {}, 0});
      Vertex& vx = vertices[it->second];
      vx.sum = {vx.sum.r + el.area * b.r, vx.sum.g + el.area * b.g, vx.sum.b + el.area * b.b};
      vx.weight += el.area;
      face.push_back(it->second);
    }
    faces.push_back(std::move(face));
  }
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
              vertices.size());
    out.print("property uchar red\nproperty uchar green\nproperty uchar blue\n");
    out.print(
        "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n");
    out.print("element face {}\nproperty list uchar int vertex_indices\nend_header\n",
              faces.size());
    for (const Vertex& v : vertices) {
      const Rgb c{v.sum.r / v.weight, v.sum.g / v.weight, v.sum.b / v.weight};
      out.print("{:.9g} {:.9g} {:.9g} {} {} {} {:.6g} {:.6g} {:.6g}\n", v.p.x, v.p.y, v.p.z,
                tone(c.r), tone(c.g), tone(c.b), c.r, c.g, c.b);
    }
    for (const std::vector<uint32_t>& f : faces) {
      out.print("{}", f.size());
      for (uint32_t i : f) out.print(" {}", i);
      out.print("\n");
    }
  } catch (const std::exception& e) {
    throw InputError(path, 0, std::string("cannot write: ") + e.what());
  }
}

}  // namespace gv
