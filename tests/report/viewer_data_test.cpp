// globalvis view (viewer.html, paper §7.5): the readers of a run's files, and the data embedded in
// the page checked against the run's files as the test parses them itself.
#include "report/viewer_data.h"

#include <gtest/gtest.h>

#include <regex>

#include "report/run_files.h"
#include "report/run_fixture.h"
#include "support/temp_dir.h"
#include "util/input_error.h"

namespace gv {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// The JSON of script#gv-data in a viewer page.
json embeddedData(const std::string& page) {
  const std::string open = "<script id=\"gv-data\" type=\"application/json\">";
  const size_t begin = page.find(open);
  if (begin == std::string::npos) return nullptr;
  const size_t end = page.find("</script>", begin);
  return json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

size_t linesStartingWith(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

TEST(RunFiles, ObjPolygonsWithGroupsAndNegativeIndices) {
  const fs::path dir = test::scratchDir();
  const auto path = test::writeFile(dir / "p.obj",
                                    "# two faces\ng portal_3_1_2\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                    "f 1 2 3\ng cell_7\nv 0 0 1\nf -1 -2/5 -3//1\n");
  const std::vector<NamedPolygon> polygons = readObjPolygons(path);
  ASSERT_EQ(polygons.size(), 2u);
  EXPECT_EQ(polygons[0].group, "portal_3_1_2");
  EXPECT_EQ(groupNumbers(polygons[0].group, 3, path), (std::vector<long>{3, 1, 2}));
  EXPECT_EQ(groupNumbers(polygons[1].group, 1, path), (std::vector<long>{7}));
  ASSERT_EQ(polygons[1].vertices.size(), 3u);
  EXPECT_EQ(polygons[1].vertices[0].z, 1.0);  // -1 = the last vertex so far
  EXPECT_EQ(polygons[1].vertices[2].x, 1.0);  // -3
  EXPECT_THROW(groupNumbers("cell_x", 1, path), InputError);
}

TEST(RunFiles, MalformedFilesNameFileAndLine) {
  const fs::path dir = test::scratchDir();
  const auto obj = test::writeFile(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
  try {
    readObjPolygons(obj);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3u);
  }
  const auto ply = test::writeFile(dir / "bad.ply",
                                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\n"
                                   "property double y\nproperty double z\nproperty uchar red\n"
                                   "property uchar green\nproperty uchar blue\nelement face 1\n"
                                   "property list uchar int vertex_indices\nend_header\n"
                                   "0 0 0 1 2 3\n3 0 0 4\n");
  try {
    readElementsPly(ply);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 14u) << e.what();
  }
  const auto rad = test::writeFile(dir / "radiosity.txt", "# c\n0 1 1 1\n2 0 0 0\n");
  EXPECT_THROW(readRadiosityTxt(rad, 3), InputError);
  const auto short_ = test::writeFile(dir / "short.txt", "0 1 1 1\n");
  EXPECT_THROW(readRadiosityTxt(short_, 2), InputError);
}

TEST(ViewCli, PageEmbedsTheRunAsItsFilesSayAndTheBundle) {
#ifndef GV_VIEWER_BUNDLE
  GTEST_SKIP() << "viewer not built (GV_BUILD_VIEWER=OFF)";
#else
  std::string error;
  const fs::path& run = test::smallRun(&error);
  ASSERT_FALSE(run.empty()) << error;
  const fs::path out = test::scratchDir() / "viewer.html";
  const auto r = test::runCli("view " + test::quoted(run) + " -o " + test::quoted(out));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string page = test::readFile(out);
  const std::string bundle = test::readFile(GV_VIEWER_BUNDLE);
  ASSERT_GT(bundle.size(), 1000u);
  EXPECT_NE(page.find(bundle), std::string::npos) << "the bundle is not inlined as is";
  const json data = embeddedData(page);
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data["format"], "globalvis-viewer-1");

  const std::string patchesObj = test::readFile(run / "vis" / "patches.obj");
  const size_t patches = linesStartingWith(patchesObj, "f ");
  EXPECT_EQ(data["patches"]["sizes"].size(), patches);
  EXPECT_EQ(data["patches"]["material"].size(), patches);
  EXPECT_EQ(data["radiosity"].size(), 3 * patches);

  // visibility.txt, parsed here: every pair and blocker list in file order.
  std::istringstream vis(test::readFile(run / "vis" / "visibility.txt"));
  std::vector<uint32_t> s, rr, counts, blockers;
  for (std::string line; std::getline(vis, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    uint32_t a, b, n;
    ss >> a >> b >> n;
    s.push_back(a);
    rr.push_back(b);
    counts.push_back(n);
    for (uint32_t i = 0, x; i < n && ss >> x; ++i) blockers.push_back(x);
  }
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(data["pairs"]["s"].get<std::vector<uint32_t> >(), s);
  EXPECT_EQ(data["pairs"]["r"].get<std::vector<uint32_t> >(), rr);
  EXPECT_EQ(data["pairs"]["blockerCounts"].get<std::vector<uint32_t> >(), counts);
  EXPECT_EQ(data["pairs"]["blockers"].get<std::vector<uint32_t> >(), blockers);

  const std::string cellsObj = test::readFile(run / "cells" / "cells.obj");
  EXPECT_EQ(data["cells"]["sizes"].size(), linesStartingWith(cellsObj, "f "));
  EXPECT_EQ(data["cellCount"].get<size_t>(), linesStartingWith(cellsObj, "g cell_"));
  const std::string portalsObj = test::readFile(run / "cells" / "portals.obj");
  EXPECT_EQ(data["portals"]["cells"].size(), 2 * linesStartingWith(portalsObj, "g portal_"));

  const std::string ply = test::readFile(run / "radiosity" / "elements.ply");
  std::smatch faces;
  ASSERT_TRUE(std::regex_search(ply, faces, std::regex("element face ([0-9]+)")));
  EXPECT_EQ(data["elements"]["faceSizes"].size(), std::stoul(faces[1]));

  // Coordinates survive the rounding to 1e-6 of the scene diagonal.
  std::istringstream objIn(patchesObj);
  std::string tag;
  double x = 0;
  for (std::string line; std::getline(objIn, line);)
    if (std::istringstream(line) >> tag >> x && tag == "v") break;
  EXPECT_NEAR(data["patches"]["xyz"][0].get<double>(), x, 1e-4);
#endif
}

TEST(ViewCli, MissingBundleAndInconsistentFilesAreClearErrors) {
  std::string error;
  const fs::path& run = test::smallRun(&error);
  ASSERT_FALSE(run.empty()) << error;
  const auto r = test::runCli("view " + test::quoted(run) + " --bundle /nonexistent/viewer.js");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("viewer bundle not found"), std::string::npos) << r.output;

  const fs::path dir = test::scratchDir();
  fs::copy(run / "vis", dir, fs::copy_options::recursive);
  test::writeFile(dir / "radiosity.txt", "0 1 1 1\n");
  const fs::path bundle = dir / "fake-viewer.js";
  test::writeFile(bundle, "void 0;");
  const auto bad = test::runCli("view " + test::quoted(dir) + " --bundle " + test::quoted(bundle));
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.output.find("radiosity.txt: 1 patches, but patches.obj has"), std::string::npos)
      << bad.output;

  const fs::path empty = dir / "empty";
  fs::create_directories(empty);
  const auto none =
      test::runCli("view " + test::quoted(empty) + " --bundle " + test::quoted(bundle));
  EXPECT_EQ(none.exitCode, 2);
  EXPECT_NE(none.output.find("no patches.obj"), std::string::npos) << none.output;
}

}  // namespace
}  // namespace gv

namespace gv {
namespace {

TEST(ViewerData, SizeLimitsDropTheBulkButKeepCounts) {
  std::string error;
  const std::filesystem::path& run = test::smallRun(&error);
  ASSERT_FALSE(run.empty()) << error;
  const RunFiles files = findRunFiles(run);
  const nlohmann::json full = viewerDataJson(files, "full");
  ASSERT_TRUE(full["pairs"]["blockersEmbedded"].get<bool>());
  ASSERT_FALSE(full["elements"].is_null());
  ASSERT_TRUE(full["notes"].empty());

  ViewerDataOptions small;
  small.maxBlockerEntries = 0;
  small.maxElementVertices = 0;
  const nlohmann::json cut = viewerDataJson(files, "cut", small);
  EXPECT_FALSE(cut["pairs"]["blockersEmbedded"].get<bool>());
  EXPECT_TRUE(cut["pairs"]["blockers"].empty());
  EXPECT_EQ(cut["pairs"]["blockerCounts"], full["pairs"]["blockerCounts"]);
  EXPECT_TRUE(cut["elements"].is_null());
  EXPECT_EQ(cut["radiosity"], full["radiosity"]);  // per-patch shading remains
  EXPECT_EQ(cut["notes"].size(), 2u);
}

}  // namespace
}  // namespace gv
