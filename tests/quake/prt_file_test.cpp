// Tests of the .prt reader: hand-written PRT1/PRT2 files, the shared real files, and bad input
// (every error names file and line).
#include "quake/prt_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "util/input_error.h"
#include "visibility/portal_clipping.h"

namespace gv {
namespace {

PrtFile parse(const std::string& text) {
  std::istringstream in(text);
  return parsePrt(in, "test.prt");
}

// Expects an InputError at `line` whose message contains `what`.
void expectError(const std::string& text, size_t line, const std::string& what) {
  try {
    parse(text);
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test.prt:"), std::string::npos) << e.what();
  }
}

TEST(PrtFile, ReadsHandWrittenPrt1) {
  const PrtFile prt = parse(
      "PRT1\n3\n2\n"
      "4 0 1 (1 0 0) (1 1 0) (1 1 1) (1 0 1) \n"
      "3 1 2 (2 0 0) (2 1 0) (2 0 1)\r\n");
  EXPECT_EQ(prt.version, 1);
  EXPECT_EQ(prt.leafCount, 3u);
  EXPECT_EQ(prt.clusterCount, 3u);
  ASSERT_EQ(prt.portals.size(), 2u);
  EXPECT_EQ(prt.portals[0].clusterA, 0);
  EXPECT_EQ(prt.portals[0].clusterB, 1);
  EXPECT_EQ(prt.portals[0].line, 4u);
  EXPECT_EQ(prt.portals[1].winding.size(), 3u);
  EXPECT_EQ(prt.portals[1].winding[2], Vec3(2, 0, 1));
  EXPECT_EQ(prt.leafCluster, (std::vector<int>{0, 1, 2}));
}

TEST(PrtFile, ReadsHandWrittenPrt2WithWrappedClusterList) {
  const PrtFile prt = parse(
      "PRT2\n5\n2\n1\n"
      "4 0 1 (1 0 0) (1 1 0) (1 1 1) (1 0 1)\n"
      "0 3 -1\n"
      "4 1\n2 -1\n");
  EXPECT_EQ(prt.version, 2);
  EXPECT_EQ(prt.leafCount, 5u);
  EXPECT_EQ(prt.clusterCount, 2u);
  EXPECT_EQ(prt.leafCluster, (std::vector<int>{0, 1, 1, 0, 1}));
  EXPECT_EQ(prt.clusterLeafs[1], (std::vector<int>{1, 2, 4}));
}

TEST(PrtFile, BadInputNamesFileAndLine) {
  expectError("PRT3\n1\n0\n", 1, "PRT1 or PRT2");
  expectError("", 0, "header");
  expectError("PRT1\nx\n0\n", 2, "integer");
  expectError("PRT1\n-2\n0\n", 2, "implausible");
  expectError("PRT1\n2\n2\n3 0 1 (0 0 0) (1 0 0) (0 1 0)\n", 4, "end of file");
  expectError("PRT1\n2\n1\n3 0 1 (0 0 0) (1 0 0)\n", 4, "expected '('");
  expectError("PRT1\n2\n1\n3 0 1 (0 0 0) (1 0 0) (0 1 0) (1 1 1)\n", 4, "more points");
  expectError("PRT1\n2\n1\n3 0 1 (0 0 0) (1 nan 0) (0 1 0)\n", 4, "non-finite");
  expectError("PRT1\n2\n1\n3 0 1 (0 0 0) (1 inf 0) (0 1 0)\n", 4, "non-finite");
  expectError("PRT1\n2\n1\n3 0 1 (0 0 0) (1 1e999 0) (0 1 0)\n", 4, "number");
  expectError("PRT1\n2\n1\n3 0 2 (0 0 0) (1 0 0) (0 1 0)\n", 4, "out of range");
  expectError("PRT1\n2\n1\n3 -1 1 (0 0 0) (1 0 0) (0 1 0)\n", 4, "out of range");
  expectError("PRT1\n2\n1\n2 0 1 (0 0 0) (1 0 0)\n", 4, "3 or more");
  expectError("PRT2\n2\n1\n0\n0 7 -1\n", 5, "leaf index out of range");
  expectError("PRT2\n2\n2\n0\n0 -1\n0 -1\n", 6, "already in cluster");
  expectError("PRT2\n2\n1\n0\n0 -1\n", 5, "in no cluster");
  expectError("PRT2\n2\n1\n0\n0 1 -1 5\n", 5, "after the -1");
  expectError("PRT1\n1\n0\nextra\n", 4, "unexpected text");
}

TEST(PrtFile, MissingFile) {
  try {
    readPrtFile("/nonexistent/dir/map.prt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0u);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/map.prt"), std::string::npos);
  }
}

TEST(PrtFile, ReadsEverySharedMapAndTheWindingConvention) {
  const std::filesystem::path dir = std::filesystem::path(GV_SHARED_DATA_DIR) / "quake";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no shared data at " << dir;
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".prt") continue;
    ++files;
    const PrtFile prt = readPrtFile(entry.path().string());
    EXPECT_GT(prt.portals.size(), 0u) << entry.path();
    // The convention the PVS relies on: the Newell normal of the file's winding points from
    // clusterA into clusterB. Check it by the other portals of both cells (cells are convex, so
    // their other portals lie behind/in front of this one): no portal may vote against it.
    std::vector<std::vector<size_t>> byCell(prt.clusterCount);
    for (size_t i = 0; i < prt.portals.size(); ++i) {
      byCell[prt.portals[i].clusterA].push_back(i);
      byCell[prt.portals[i].clusterB].push_back(i);
    }
    size_t against = 0;
    for (size_t i = 0; i < prt.portals.size(); ++i) {
      const PrtPortal& p = prt.portals[i];
      const Vec3 n = normalize(newellNormal(p.winding));
      const double off = dot(n, p.winding[0]);
      double vote = 0;
      for (int side = 0; side < 2; ++side) {
        const int cell = side == 0 ? p.clusterA : p.clusterB;
        for (size_t j : byCell[cell]) {
          if (j == i) continue;
          for (const Vec3& v : prt.portals[j].winding) {
            const double d = dot(n, v) - off;
            if (std::abs(d) > 0.5) vote += (side == 0 ? -1 : 1) * (d > 0 ? 1 : -1);
          }
        }
      }
      against += vote < 0;
    }
    EXPECT_EQ(against, 0u) << entry.path();
  }
  EXPECT_GE(files, 10u);
}

}  // namespace
}  // namespace gv
