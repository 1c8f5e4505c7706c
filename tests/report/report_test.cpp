// globalvis report (report.html, paper §7): the HTML helpers against known values, the Fig. 13
// chart's geometry, and the page for a real run checked against the run's own files.
#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "report/fig13_chart.h"
#include "report/html_page.h"
#include "report/report_html.h"
#include "report/run_fixture.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

size_t countOf(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// n with thousands separators, as the report prints counts (written independently here).
std::string withCommas(size_t n) {
  std::string reversed;
  for (size_t digits = 0; n > 0 || digits == 0; n /= 10, ++digits) {
    if (digits > 0 && digits % 3 == 0) reversed += ',';
    reversed += char('0' + n % 10);
  }
  return {reversed.rbegin(), reversed.rend()};
}

/// A tiny valid PNG (1x1, one red pixel), written out byte by byte.
const std::string& tinyPng() {
  static const std::string png = [] {
    const unsigned char bytes[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
        0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00,
        0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x78,
        0x9c, 0x63, 0xf8, 0xcf, 0xc0, 0x00, 0x00, 0x03, 0x01, 0x01, 0x00, 0xc9, 0xfe, 0x92,
        0xef, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    return std::string(reinterpret_cast<const char*>(bytes), sizeof bytes);
  }();
  return png;
}

TEST(ReportHtml, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(base64Encode(""), "");
  EXPECT_EQ(base64Encode("f"), "Zg==");
  EXPECT_EQ(base64Encode("fo"), "Zm8=");
  EXPECT_EQ(base64Encode("foo"), "Zm9v");
  EXPECT_EQ(base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64Encode(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(ReportHtml, EscapingKeepsMarkupInert) {
  EXPECT_EQ(htmlEscape("<a href=\"x\">&'</a>"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
  const json value = {{"title", "</script><script>alert(1)</script>"}, {"n", {1, 2.5}}};
  const std::string text = jsonForScript(value);
  EXPECT_EQ(text.find('<'), std::string::npos) << text;
  EXPECT_EQ(json::parse(text), value);  // still the same JSON
}

TEST(ReportHtml, ViewerPageRefusesABundleThatClosesItsScript) {
  EXPECT_THROW(viewerPageHtml("t", "var s = '</SCRIPT>';", json::object()), std::invalid_argument);
  const std::string page = viewerPageHtml("a <b>", "console.log(1)", json{{"k", "</x>"}});
  EXPECT_NE(page.find("<title>a &lt;b&gt;</title>"), std::string::npos);
  EXPECT_EQ(countOf(page, "</script>"), 2u);  // exactly the two elements' own ends
}

TEST(ReportHtml, Fig13BarsAreProportionalToTheCounts) {
  const std::vector<uint64_t> successes{0, 10, 40, 20}, failures{0, 0, 5, 80};
  const std::string svg = fig13ChartSvg(successes, failures);
  EXPECT_EQ(countOf(svg, "class=\"success\""), successes.size());
  EXPECT_EQ(countOf(svg, "class=\"failure\""), failures.size());
  // Heights in the order drawn (success, failure per length): each is count * (plot / axis top),
  // the same scale for all bars.
  const std::regex height("class=\"(success|failure)\"[^>]*height=\"([0-9.]+)\"");
  std::vector<double> heights;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), height); it != std::sregex_iterator();
       ++it)
    heights.push_back(std::stod((*it)[2]));
  ASSERT_EQ(heights.size(), 8u);
  const double scale = heights[7] / 80.0;
  ASSERT_GT(scale, 0);
  const std::vector<uint64_t> order{0, 0, 10, 0, 40, 5, 20, 80};
  for (size_t i = 0; i < order.size(); ++i)
    EXPECT_NEAR(heights[i], double(order[i]) * scale, 0.11) << i;
  EXPECT_NE(fig13ChartSvg({}, {}).find("no stabbing tests"), std::string::npos);
}

TEST(ReportHtml, MissingStagesSaySoInsteadOfFailing) {
  ReportInputs in;
  in.title = "partial run";
  in.cells = json{{"patches", 12}, {"leaf_cells", 3456}, {"portals", 7}};
  const std::string page = reportHtml(in);
  EXPECT_NE(page.find("3,456"), std::string::npos);
  EXPECT_NE(page.find("No vis/stats.json"), std::string::npos);
  EXPECT_NE(page.find("No radiosity/stats.json"), std::string::npos);
  EXPECT_NE(page.find("id=\"table-1-paper\""), std::string::npos);  // the paper's rows regardless
  EXPECT_NE(page.find("145,846"), std::string::npos);
}

TEST(ReportCli, ReportOfARunHasItsTablesAndFigures) {
  std::string error;
  const fs::path& run = test::smallRun(&error);
  ASSERT_FALSE(run.empty()) << error;
  const fs::path dir = test::scratchDir();
  fs::copy(run, dir, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  test::writeFile(dir / "radiosity" / "render.png", tinyPng());

  const auto r = test::runCli("report " + test::quoted(dir));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string page = test::readFile(dir / "report.html");
  for (const char* id : {"table-7-1", "table-7-2", "table-fig13", "table-7-3", "table-1-paper",
                         "table-1-run", "table-timings"})
    EXPECT_NE(page.find(std::string("id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_NE(page.find("<svg class=\"chart\""), std::string::npos);

  // Figures of the run, counted from its files rather than taken from its stats.
  const std::string cellsObj = test::readFile(dir / "cells" / "cells.obj");
  std::set<std::string> cells;
  const std::regex group("\ng (cell_[0-9]+)");
  for (auto it = std::sregex_iterator(cellsObj.begin(), cellsObj.end(), group);
       it != std::sregex_iterator(); ++it)
    cells.insert((*it)[1]);
  std::istringstream vis(test::readFile(dir / "vis" / "visibility.txt"));
  size_t pairs = 0, visible = 0;
  for (std::string line; std::getline(vis, line);) {
    if (line.empty() || line[0] == '#') continue;
    ++pairs;
    std::istringstream ss(line);
    size_t s, rr, n;
    ss >> s >> rr >> n;
    if (n == 0) ++visible;
  }
  ASSERT_GT(pairs, visible);  // the scene has PARTIAL pairs
  EXPECT_NE(page.find("<td>" + withCommas(cells.size()) + "</td>"), std::string::npos)
      << cells.size();
  EXPECT_NE(page.find("<td>" + withCommas(pairs) + " ("), std::string::npos) << pairs;
  EXPECT_NE(page.find("<td>" + withCommas(visible) + " ("), std::string::npos) << visible;
  EXPECT_NE(page.find("data:image/png;base64," + base64Encode(tinyPng())), std::string::npos);
  EXPECT_NE(page.find("radiosity/render.png"), std::string::npos);
  EXPECT_EQ(page.find("src=\"viewer.html\""), std::string::npos);  // no viewer written yet

#ifdef GV_VIEWER_BUNDLE
  // --viewer writes the viewer first and frames it; -o elsewhere keeps the link relative.
  const auto withViewer = test::runCli("report --viewer " + test::quoted(dir) + " -o " +
                                       test::quoted(dir / "cells" / "r.html"));
  ASSERT_EQ(withViewer.exitCode, 0) << withViewer.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "viewer.html"));
  EXPECT_NE(test::readFile(dir / "cells" / "r.html").find("src=\"../viewer.html\""),
            std::string::npos);
#endif
}

TEST(ReportCli, EmptyDirectoryIsAnInputError) {
  const fs::path dir = test::scratchDir();
  const auto r = test::runCli("report " + test::quoted(dir));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("no cells/stats.json"), std::string::npos) << r.output;
  const auto missing = test::runCli("report /nonexistent/run");
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.output.find("/nonexistent/run: not a directory"), std::string::npos);
}

}  // namespace
}  // namespace gv
