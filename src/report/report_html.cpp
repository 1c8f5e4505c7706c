// The run report page (see report_html.h): tables of the paper's §7 figures beside this run's,
// the Fig. 13 chart, pictures as data: URIs, timings, and a link to (and frame of) the viewer.
#include "report/report_html.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "report/fig13_chart.h"
#include "report/html_page.h"
#include "report/run_files.h"
#include "util/input_error.h"

namespace gv {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kMissing = "—";

/// The value at JSON pointer `pointer` of `doc`, or nullptr if absent or not a number.
const json* number(const std::optional<json>& doc, const char* pointer) {
  if (!doc) return nullptr;
  const json::json_pointer p(pointer);
  if (!doc->contains(p)) return nullptr;
  const json& v = (*doc)[p];
  return v.is_number() ? &v : nullptr;
}

std::string withCommas(double value) {
  const std::string digits = fmt::format("{:.0f}", std::abs(value));
  std::string out = value <= -0.5 ? "-" : "";
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

/// A count with thousands separators, or "—".
std::string count(const json* v) {
  return v ? withCommas(v->get<double>()) : kMissing;
}

/// A number with `digits` decimals, or "—".
std::string fixed(const json* v, int digits) {
  return v ? fmt::format("{:.{}f}", v->get<double>(), digits) : kMissing;
}

std::string ratio(const json* a, const json* b, int digits) {
  if (!a || !b || b->get<double>() == 0) return kMissing;
  return fmt::format("{:.{}f}", a->get<double>() / b->get<double>(), digits);
}

std::string percentOf(const json* part, double whole) {
  if (!part || whole <= 0) return "";
  return fmt::format(" ({:.1f} %)", 100.0 * part->get<double>() / whole);
}

/// A table with a header row; cells are HTML already.
std::string table(const std::string& id, const std::vector<std::string>& header,
                  const std::vector<std::vector<std::string>>& rows) {
  std::string out = "<table id=\"" + id + "\">\n<thead><tr>";
  for (const std::string& h : header) out += "<th>" + h + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (size_t i = 0; i < row.size(); ++i)
      out += (i == 0 ? "<th>" : "<td>") + row[i] + (i == 0 ? "</th>" : "</td>");
    out += "</tr>\n";
  }
  return out + "</tbody></table>\n";
}

std::string missingSection(const char* what) {
  return fmt::format("<p class=\"missing\">No {} in this run directory.</p>\n", what);
}

std::string cellsSection(const ReportInputs& in) {
  std::string out = "<section id=\"sec-7-1\"><h2>§7.1 Spatial subdivision</h2>\n";
  if (!in.cells && !in.vis)
    return out + missingSection("cells/stats.json or vis/stats.json") + "</section>\n";
  const auto& c = in.cells;
  const auto& v = in.vis;
  auto row = [&](const char* label, const char* paper, const char* key, int digits) {
    const std::string pointer = std::string("/subdivision/") + key;
    const std::string top = std::string("/") + key;
    return std::vector<std::string>{
        label, paper,
        digits < 0 ? count(number(c, top.c_str())) : fixed(number(c, top.c_str()), digits),
        digits < 0 ? count(number(v, pointer.c_str())) : fixed(number(v, pointer.c_str()), digits)};
  };
  out += table(
      "table-7-1",
      {"", "paper", "this run: <code>cells/</code>", "subdivision of <code>vis/</code>"},
      {row("patches", "403", "patches", -1), row("planes", kMissing, "planes", -1),
       row("BSP nodes", kMissing, "bsp_nodes", -1), row("leaf cells", "220", "leaf_cells", -1),
       row("boundary faces per cell", "5.99", "mean_boundary_faces_per_cell", 2),
       row("coaffine patches per cell", "5.87", "mean_coaffine_patches_per_cell", 2),
       row("portals", "525", "portals", -1),
       row("portals per cell", kMissing, "mean_portals_per_cell", 2),
       row("BSP seconds", "about 30 (CPU, SGI VGX)", "bsp_seconds", 3),
       row("portal seconds", "about 7 (CPU)", "portal_seconds", 3)});
  out +=
      "<p class=\"note\">The <code>vis</code> stage builds its own subdivision (its stop rule "
      "may differ from the <code>cells</code> stage's: see "
      "<code>scripts/run-default.sh</code>).</p>\n";
  return out + "</section>\n";
}

std::string visibilitySection(const ReportInputs& in) {
  std::string out = "<section id=\"sec-7-2\"><h2>§7.2 Visibility propagation</h2>\n";
  if (!in.vis) return out + missingSection("vis/stats.json") + "</section>\n";
  const auto& v = in.vis;
  const json* patches = number(v, "/visibility/patches");
  const json* pairs = number(v, "/visibility/patch_pairs");
  const json* listed = number(v, "/visibility/pairs_listed");
  const json* partial = number(v, "/visibility/pairs_partial");
  const json* visible = number(v, "/visibility/pairs_visible");
  const json* cells = number(v, "/visibility/cells");
  const json* cellTests = number(v, "/visibility/cell_stabbing_tests");
  const json* patchTests = number(v, "/visibility/patch_stabbing_tests");
  const double listedCount = listed ? listed->get<double>() : 0;
  std::string partners = kMissing;
  if (listed && patches && patches->get<double>() > 0)
    partners = fmt::format("{:.1f}", 2 * listed->get<double>() / patches->get<double>());
  const json* threads = number(v, "/visibility/threads");
  out +=
      table("table-7-2", {"", "paper", "this run"},
            {{"patches", "403", count(patches)},
             {"patch pairs", "81,003", count(pairs)},
             {"pairs mutually visible (listed)", "4,391 (5.4 %)",
              count(listed) + percentOf(listed, pairs ? pairs->get<double>() : 0)},
             {"PARTIAL", "2,814 (64.1 %)", count(partial) + percentOf(partial, listedCount)},
             {"VISIBLE", "1,577 (35.9 %)", count(visible) + percentOf(visible, listedCount)},
             {"partners per patch", "22", partners},
             {"cell-to-cell stabbing tests", "10,128", count(cellTests)},
             {"&nbsp;&nbsp;per cell", "46", ratio(cellTests, cells, 1)},
             {"patch stabbing tests", "16,055", count(patchTests)},
             {"&nbsp;&nbsp;per patch", "40", ratio(patchTests, patches, 1)},
             {"&nbsp;&nbsp;unresolved (counted visible)", kMissing,
              count(number(v, "/visibility/unresolved_stabbing_tests"))},
             {"mean portal sequence length", "just over 5",
              fixed(number(v, "/visibility/mean_sequence_length"), 2)},
             {"visible cell pairs", kMissing, count(number(v, "/visibility/cell_pairs_visible"))},
             {"seconds", "300 (CPU)",
              fixed(number(v, "/visibility/seconds/total"), 2) +
                  (threads ? fmt::format(" (wall, {} threads)", threads->get<int>()) : "")}});

  if (!in.verify.empty())
    out +=
        "<p>Independent check by ray casting (<code>globalvis verify</code>, "
        "<code>vis/verify.txt</code>):</p>\n<pre id=\"verify\">" +
        htmlEscape(in.verify) + "</pre>\n";
  out += "<h3 id=\"fig13\">Fig. 13: stabbing successes and failures, by sequence length</h3>\n";
  std::vector<uint64_t> successes, failures;
  if (v->contains("visibility") && (*v)["visibility"].contains("fig13_successes_by_length")) {
    successes = (*v)["visibility"]["fig13_successes_by_length"].get<std::vector<uint64_t>>();
    failures = (*v)["visibility"].value("fig13_failures_by_length", std::vector<uint64_t>{});
  }
  out += fig13ChartSvg(successes, failures);
  std::vector<std::vector<std::string>> rows;
  for (size_t n = 0; n < std::max(successes.size(), failures.size()); ++n) {
    const double s = n < successes.size() ? double(successes[n]) : 0;
    const double f = n < failures.size() ? double(failures[n]) : 0;
    if (s + f == 0) continue;
    rows.push_back({std::to_string(n), withCommas(s), withCommas(f),
                    fmt::format("{:.1f} %", 100 * s / (s + f))});
  }
  out += table("table-fig13", {"portals", "stabbed", "not stabbed", "stabbed share"}, rows);
  out += "</section>\n";

  out += "<section id=\"sec-7-3\"><h2>§7.3 Blocker detection</h2>\n";
  out += table("table-7-3", {"", "paper", "this run"},
               {{"blockers per PARTIAL pair", "5",
                 fixed(number(v, "/visibility/mean_blockers_per_partial"), 2)},
                {"shaft cull (patches meeting conv(S, R)) per PARTIAL pair",
                 "12 or more (the Fig. 9 example of §5, which has 6 blockers)",
                 fixed(number(v, "/visibility/mean_shaft_cull_per_partial"), 2) +
                     fmt::format(" (over {} pairs)",
                                 count(number(v, "/visibility/shaft_cull_sampled_pairs")))}});
  return out + "</section>\n";
}

/// The paper's Table 1 as printed (§7.4).
std::string paperTable1() {
  return table("table-1-paper", {"", "input links", "refine 1", "links", "refine 2", "links"},
               {{"V", "1,577 (35.9 %)", "→ V 170,440 (87.6 %)", "V 176,474", "→ V 218,420 (87.6 %)",
                 "V 225,763"},
                {"", "", "P → V 6,034 (3.1 %)", "", "P → V 7,343 (2.9 %)", ""},
                {"P", "2,814 (64.1 %)", "P → P 16,889 (8.7 %)", "P 16,889", "P → P 22,157 (8.9 %)",
                 "P 22,157"},
                {"", "", "P → I 1,096 (0.6 %)", "", "P → I 1,339 (0.5 %)", ""},
                {"total", "4,391", "194,459", "193,363", "249,259", "247,920"},
                {"patches (elements)", "403", "", "15,039", "", "17,347"},
                {"interactions", "4,391", "145,846 (11 s)", "", "186,703 (50 s)", ""}});
}

std::string radiositySection(const ReportInputs& in) {
  std::string out = "<section id=\"sec-7-4\"><h2>§7.4 Table 1: link evolution</h2>\n";
  out += "<h3>Paper</h3>\n" + paperTable1();
  out += "<h3>This run</h3>\n";
  if (!in.radiosity) return out + missingSection("radiosity/stats.json") + "</section>\n";
  const json& r = *in.radiosity;
  out += fmt::format(
      "<p>Visibility of the links: <code>{}</code>; {} patches, {} candidate pairs, "
      "{} facing pairs.</p>\n",
      htmlEscape(r.value("visibility", std::string(kMissing))),
      count(number(in.radiosity, "/patches")), count(number(in.radiosity, "/candidate_pairs")),
      count(number(in.radiosity, "/facing_pairs")));
  std::vector<std::vector<std::string>> rows;
  if (r.contains("rounds") && r["rounds"].is_array()) {
    for (const json& round : r["rounds"]) {
      const std::optional<json> rd = round;
      const json* created = number(rd, "/links_created/total");
      const double c = created ? created->get<double>() : 0;
      rows.push_back({count(number(rd, "/round")),
                      count(number(rd, "/links_created/visible")) +
                          percentOf(number(rd, "/links_created/visible"), c),
                      count(number(rd, "/links_created/partial")) +
                          percentOf(number(rd, "/links_created/partial"), c),
                      count(number(rd, "/links_created/invisible")) +
                          percentOf(number(rd, "/links_created/invisible"), c),
                      count(created), count(number(rd, "/links/visible")),
                      count(number(rd, "/links/partial")), count(number(rd, "/links/total")),
                      count(number(rd, "/elements")), count(number(rd, "/interactions")),
                      fixed(number(rd, "/refine_seconds"), 2),
                      fixed(number(rd, "/solve_seconds"), 2)});
    }
  }
  out += table("table-1-run",
               {"round", "created V", "created P", "created I", "created", "links V", "links P",
                "links", "elements", "interactions", "refine s", "solve s"},
               rows);
  out += fmt::format(
      "<p>Totals: {} links, {} elements, {} interactions, {} rays, {} s, converged: {}.</p>\n",
      count(number(in.radiosity, "/totals/links")), count(number(in.radiosity, "/totals/elements")),
      count(number(in.radiosity, "/totals/interactions")),
      count(number(in.radiosity, "/totals/rays")),
      fixed(number(in.radiosity, "/totals/seconds"), 2),
      r.contains("totals") && r["totals"].value("converged", false) ? "yes" : "no");
  out +=
      "<p class=\"note\">Round 0 creates the initial links between the input patches (I: "
      "pairs found invisible and discarded); each later round refines links and creates "
      "their children. The paper's P → V / P → I transitions are not recorded per link here: "
      "created links are counted by their class.</p>\n";
  return out + "</section>\n";
}

std::string timingsSection(const ReportInputs& in) {
  std::vector<std::vector<std::string>> rows;
  if (in.timings && in.timings->contains("steps")) {
    for (const json& step : (*in.timings)["steps"]) {
      const std::optional<json> s = step;
      rows.push_back({htmlEscape(step.value("name", std::string(kMissing))),
                      "wall clock, whole step", fixed(number(s, "/seconds"), 2)});
    }
  }
  auto add = [&](const char* stage, const char* what, const std::optional<json>& doc,
                 const char* p) {
    if (const json* v = number(doc, p)) rows.push_back({stage, what, fixed(v, 3)});
  };
  add("cells", "BSP", in.cells, "/bsp_seconds");
  add("cells", "portals", in.cells, "/portal_seconds");
  add("vis", "cell-to-cell visibility", in.vis, "/visibility/seconds/cells");
  add("vis", "patch visibility", in.vis, "/visibility/seconds/patches");
  add("vis", "blocker lists", in.vis, "/visibility/seconds/blockers");
  add("vis", "total", in.vis, "/visibility/seconds/total");
  if (in.radiosity && in.radiosity->contains("rounds")) {
    for (const json& round : (*in.radiosity)["rounds"]) {
      const std::optional<json> rd = round;
      const std::string label = "round " + count(number(rd, "/round"));
      if (const json* v = number(rd, "/refine_seconds"))
        rows.push_back({"radiosity", label + " refine", fixed(v, 3)});
      if (const json* v = number(rd, "/solve_seconds"))
        rows.push_back({"radiosity", label + " solve", fixed(v, 3)});
    }
  }
  add("radiosity", "total", in.radiosity, "/totals/seconds");
  std::string out = "<section id=\"timings\"><h2>Timings per stage</h2>\n";
  if (rows.empty()) return out + missingSection("timings") + "</section>\n";
  return out + table("table-timings", {"stage", "part", "seconds"}, rows) + "</section>\n";
}

std::string picturesSection(const ReportInputs& in) {
  std::string out = "<section id=\"pictures\"><h2>Pictures (Fig. 14)</h2>\n";
  if (in.pictures.empty())
    return out + missingSection("PNG pictures (radiosity/*.png)") + "</section>\n";
  out += "<div class=\"pictures\">\n";
  for (const ReportPicture& p : in.pictures) {
    out += fmt::format(
        "<figure><img alt=\"{0}\" src=\"data:image/png;base64,{1}\"><figcaption>"
        "<code>{0}</code>: {2}</figcaption></figure>\n",
        htmlEscape(p.file), base64Encode(p.png), htmlEscape(p.caption));
  }
  return out + "</div></section>\n";
}

std::string viewerSection(const ReportInputs& in) {
  std::string out = "<section id=\"viewer\"><h2>Interactive viewer (§7.5)</h2>\n";
  if (in.viewerHref.empty())
    return out + missingSection("viewer.html (write it with `globalvis view`)") + "</section>\n";
  const std::string href = htmlEscape(in.viewerHref);
  out += fmt::format(
      "<p><a href=\"{0}\">Open the viewer</a> (its own page): click a patch to see "
      "what it sees; pick an interaction for its tube (red) and blockers (orange), as "
      "the paper's Figs. 15–17.</p>\n<iframe id=\"viewer-frame\" src=\"{0}\" "
      "title=\"globalvis viewer\"></iframe>\n",
      href);
  return out + "</section>\n";
}

constexpr const char* kStyle = R"(
body { font: 14px/1.45 system-ui, sans-serif; margin: 0 auto; max-width: 1100px; padding: 16px; color: #222; }
h1 { font-size: 22px; } h2 { font-size: 18px; margin-top: 28px; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; margin: 8px 0; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: right; white-space: nowrap; }
thead th { background: #f0f0f0; text-align: center; } tbody th { text-align: left; font-weight: normal; }
pre { background: #f6f6f6; padding: 6px 8px; border: 1px solid #ddd; white-space: pre-wrap; }
.note, .missing { color: #666; } .missing { font-style: italic; }
.pictures { display: flex; flex-wrap: wrap; gap: 12px; }
figure { margin: 0; max-width: 340px; } figure img { width: 100%; border: 1px solid #ccc; }
iframe { width: 100%; height: 640px; border: 1px solid #ccc; }
)";

/// What each known picture shows (Fig. 14 of the paper).
std::string captionOf(const std::string& file) {
  if (file == "render.png") return "the scene shaded by the radiosity solution";
  if (file == "links_visible.png") return "VISIBLE links (white), as Fig. 14 middle";
  if (file == "links_partial.png") return "PARTIAL links (green), as Fig. 14 right";
  return "picture of this run";
}

}  // namespace

std::string reportHtml(const ReportInputs& in) {
  std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
      htmlEscape(in.title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  page += "<h1>" + htmlEscape(in.title) + "</h1>\n";
  page +=
      "<p>The figures of §7 of Teller &amp; Hanrahan, <i>Global Visibility Algorithms for "
      "Illumination Computations</i> (SIGGRAPH 1993), for this run beside the paper's own "
      "(its 403-patch office on a 50-MIPS SGI VGX).</p>\n";
  if (in.vis && in.vis->contains("scene") && (*in.vis)["scene"].is_string())
    page +=
        "<p>Scene: <code>" + htmlEscape((*in.vis)["scene"].get<std::string>()) + "</code></p>\n";
  page +=
      "<nav><a href=\"#sec-7-1\">§7.1</a> · <a href=\"#sec-7-2\">§7.2</a> · <a "
      "href=\"#fig13\">Fig. 13</a> · "
      "<a href=\"#sec-7-3\">§7.3</a> · <a href=\"#sec-7-4\">Table 1</a> · <a "
      "href=\"#pictures\">pictures</a> · "
      "<a href=\"#timings\">timings</a> · <a href=\"#viewer\">viewer</a></nav>\n";
  page += cellsSection(in) + visibilitySection(in) + radiositySection(in) + picturesSection(in) +
          timingsSection(in) + viewerSection(in);
  return page + "</body>\n</html>\n";
}

ReportInputs collectReportInputs(const fs::path& dir) {
  const RunFiles files = findRunFiles(dir);
  ReportInputs in;
  in.title = "globalvis report: " + dir.string();
  in.cells = readStatsJson(files.cellsStats);
  in.vis = readStatsJson(files.visStats);
  in.radiosity = readStatsJson(files.radiosityStats);
  if (!in.cells && !in.vis && !in.radiosity)
    throw InputError(dir.string(), 0,
                     "no cells/stats.json, vis/stats.json or radiosity/stats.json "
                     "here (run `make run`, or the stages with -o DIR/cells, "
                     "DIR/vis, DIR/radiosity)");
  if (fs::is_regular_file(dir / "timings.json")) in.timings = readStatsJson(dir / "timings.json");
  if (fs::is_regular_file(dir / "vis" / "verify.txt")) {
    std::ifstream f(dir / "vis" / "verify.txt");
    std::ostringstream text;
    text << f.rdbuf();
    in.verify = text.str();
  }

  std::vector<fs::path> pngs;
  for (const fs::path& folder : {dir / "radiosity", dir}) {
    if (!fs::is_directory(folder)) continue;
    std::vector<fs::path> here;
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.is_regular_file() && entry.path().extension() == ".png")
        here.push_back(entry.path());
    std::sort(here.begin(), here.end(), [](const fs::path& a, const fs::path& b) {
      auto rank = [](const fs::path& p) {
        const std::string n = p.filename().string();
        return n == "render.png"          ? 0
               : n == "links_visible.png" ? 1
               : n == "links_partial.png" ? 2
                                          : 3;
      };
      return std::pair(rank(a), a.filename()) < std::pair(rank(b), b.filename());
    });
    pngs.insert(pngs.end(), here.begin(), here.end());
  }
  for (const fs::path& p : pngs) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream bytes;
    bytes << f.rdbuf();
    if (!f) throw InputError(p.string(), 0, "cannot be read");
    const std::string name = fs::relative(p, dir).string();
    in.pictures.push_back({name, captionOf(p.filename().string()), bytes.str()});
  }
  if (fs::is_regular_file(dir / "viewer.html")) in.viewerHref = "viewer.html";
  return in;
}

}  // namespace gv
