// The executable end to end: help, info, and bad input ending in a message and a non-zero exit
// (never a crash: a signal would show as exit code -1 here).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "support/run_cli.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

using test::quoted;
using test::runCli;

TEST(Cli, HelpListsTheSubcommands) {
  const auto r = runCli("help");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.output.find("info"), std::string::npos);
  EXPECT_NE(r.output.find("gen"), std::string::npos);
}

TEST(Cli, InfoPrintsCounts) {
  const auto dir = test::scratchDir();
  const auto obj = dir / "quad.obj";
  test::writeFile(obj, "v 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\nf 1 2 3 4\nf 1 1 2\n");
  const auto r = runCli("info " + quoted(obj));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("faces in     2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("patches      1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("dropped      1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("total area   6"), std::string::npos) << r.output;
}

TEST(CliBadInput, MissingFile) {
  const auto r = runCli("info /nonexistent/x.obj");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("/nonexistent/x.obj: file not found"), std::string::npos) << r.output;
}

TEST(CliBadInput, NanCoordinateNamesFileAndLine) {
  const auto dir = test::scratchDir();
  const auto obj = dir / "nan.obj";
  test::writeFile(obj, "v 0 0 0\nv NaN 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto r = runCli("info " + quoted(obj));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("nan.obj:2:"), std::string::npos) << r.output;
}

TEST(CliBadInput, EmptyScene) {
  const auto dir = test::scratchDir();
  const auto obj = dir / "empty.obj";
  test::writeFile(obj, "# nothing here\n");
  const auto r = runCli("info " + quoted(obj));
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("no faces"), std::string::npos) << r.output;
}

TEST(CliBadInput, UnknownOptionAndSubcommand) {
  auto r = runCli("info --frobnicate x.obj");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("--frobnicate"), std::string::npos) << r.output;
  r = runCli("frobnicate");
  EXPECT_EQ(r.exitCode, 1);
  r = runCli("");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("subcommand"), std::string::npos) << r.output;
}

TEST(Cli, VisWithContactSplitIsVerifiedOnItsPieces) {
  // The Cornell box's blocks stand on the floor: --contact-split cuts the floor along their
  // footprints (19 -> 31 patches); the result must still pass the independent ray check.
  const auto dir = test::scratchDir();
  const std::string obj = (dir / "c.obj").string(), out = (dir / "out").string();
  ASSERT_EQ(test::runCli("gen cornell -o '" + obj + "'").exitCode, 0);
  const auto vis = test::runCli("vis '" + obj + "' -o '" + out + "' --contact-split");
  ASSERT_EQ(vis.exitCode, 0) << vis.output;
  EXPECT_NE(vis.output.find("patches 31"), std::string::npos) << vis.output;
  const auto r = test::runCli("verify '" + out + "' --rays 40000 --segments 10000");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

}  // namespace
}  // namespace gv

namespace gv {
namespace {

TEST(Cli, VisWritesTheContractFiles) {
  const auto dir = test::scratchDir();
  ASSERT_EQ(test::runCli("gen cornell -o '" + (dir / "c.obj").string() + "'").exitCode, 0);
  const auto r =
      test::runCli("vis '" + (dir / "c.obj").string() + "' -o '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"patches.obj", "patches.mtl", "visibility.txt", "stats.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  std::ifstream in(dir / "out" / "visibility.txt");
  size_t lines = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    uint32_t s = 0, t = 0;
    size_t n = 0;
    ASSERT_TRUE(ss >> s >> t >> n) << line;
    EXPECT_LT(s, t);
    EXPECT_LT(t, 19u);  // the Cornell box has 19 patches
    ++lines;
  }
  EXPECT_GT(lines, 10u);
}

}  // namespace
}  // namespace gv

namespace gv {
namespace {

TEST(Cli, VerifyPassesOnVisOutputAndCatchesARemovedPair) {
  const auto dir = test::scratchDir();
  const std::string obj = (dir / "c.obj").string(), out = (dir / "out").string();
  ASSERT_EQ(test::runCli("gen cornell -o '" + obj + "'").exitCode, 0);
  ASSERT_EQ(test::runCli("vis '" + obj + "' -o '" + out + "'").exitCode, 0);
  auto r = test::runCli("verify '" + out + "' --rays 20000 --segments 5000");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("OK: no violation"), std::string::npos) << r.output;

  // Drop every pair of patch 0 (the floor, which sees most of the box): a light leak to catch.
  const auto txt = std::filesystem::path(out) / "visibility.txt";
  std::ifstream in(txt);
  std::string kept;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("0 ", 0) != 0) kept += line + "\n";
  in.close();
  test::writeFile(txt, kept);
  r = test::runCli("verify '" + out + "' --rays 20000 --segments 5000");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("not listed"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace gv
