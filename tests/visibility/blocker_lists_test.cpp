// The streamed blocker lists of paper §5: BlockerLists, VisibilityTxtWriter, and propagation's
// interactionSink (the path `globalvis vis` writes visibility.txt by), checked against the graph
// computeVisibility holds in memory: the same pairs, lists and statistics, in (s, r) order.
#include "visibility/blocker_lists.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bsp/hidden_faces.h"
#include "bsp/subdivision.h"
#include "generators/maze.h"
#include "generators/office.h"
#include "input/load_scene.h"
#include "scene/scene_io.h"
#include "support/run_cli.h"
#include "support/temp_dir.h"
#include "util/input_error.h"
#include "visibility/propagation.h"
#include "visibility/visibility_graph.h"

namespace gv {
namespace {

TEST(BlockerLists, HoldsPairsInOrderAndClears) {
  BlockerLists lists;
  EXPECT_TRUE(lists.empty());
  const std::vector<uint32_t> a{3, 7, 9}, none;
  lists.add(1, 4, a);
  lists.add(1, 6, none);
  lists.add(2, 5, std::vector<uint32_t>{8});
  ASSERT_EQ(lists.size(), 3u);
  EXPECT_EQ(lists.idCount(), 4u);
  EXPECT_EQ(lists.s(0), 1u);
  EXPECT_EQ(lists.r(0), 4u);
  EXPECT_EQ(std::vector<uint32_t>(lists.blockers(0).begin(), lists.blockers(0).end()), a);
  EXPECT_TRUE(lists.blockers(1).empty());
  EXPECT_EQ(lists.r(2), 5u);
  ASSERT_EQ(lists.blockers(2).size(), 1u);
  EXPECT_EQ(lists.blockers(2)[0], 8u);
  const size_t capacity = lists.idCapacity();
  lists.clear();
  EXPECT_TRUE(lists.empty());
  EXPECT_EQ(lists.idCount(), 0u);
  EXPECT_EQ(lists.idCapacity(), capacity);  // reused without allocating
  lists.add(0, 1, none);
  EXPECT_TRUE(lists.blockers(0).empty());
}

TEST(VisibilityTxtWriter, LinesAreThePapersFormatAndReadBack) {
  const auto dir = test::scratchDir();
  VisibilityGraph g;
  g.interactions = {{0, 1, {}}, {0, 5, {2, 3}}, {4, 1000000, {7}}};
  writeVisibilityTxt(g, (dir / "a.txt").string());
  const std::string text = test::readFile(dir / "a.txt");
  EXPECT_NE(text.find("\n0 1 0\n0 5 2 2 3\n4 1000000 1 7\n"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');
  // Lists added pair by pair, or as BlockerLists, give the same bytes.
  BlockerLists lists;
  for (const Interaction& in : g.interactions) lists.add(in.s, in.r, in.blockers);
  {
    VisibilityTxtWriter w((dir / "b.txt").string());
    w.add(lists);
    w.close();
    w.close();  // idempotent
  }
  EXPECT_EQ(test::readFile(dir / "b.txt"), text);
  const VisibilityGraph back = readVisibilityTxt((dir / "b.txt").string());
  ASSERT_EQ(back.interactions.size(), 3u);
  EXPECT_EQ(back.interactions[1].blockers, (std::vector<uint32_t>{2, 3}));
  EXPECT_EQ(back.interactions[2].r, 1000000u);
}

TEST(VisibilityTxtWriter, EveryNumberOfDigitsIsWrittenAsDecimal) {
  // The writer packs the digits of small ids once and formats large ones on the fly: every
  // digit count and both sides of the switch (10^7) against std::ostringstream.
  const auto dir = test::scratchDir();
  std::vector<uint32_t> ids;
  for (uint64_t p = 1; p <= 1000000000; p *= 10)
    for (uint64_t v : {p - 1, p, p + 1, 2 * p + 7}) ids.push_back(static_cast<uint32_t>(v));
  ids.push_back(4294967295u);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::string expected;
  {
    VisibilityTxtWriter w((dir / "d.txt").string());
    for (int round = 0; round < 20000; ++round) {
      const uint32_t s = ids[size_t(round) % ids.size()], r = s + 1 + uint32_t(round % 3);
      const std::vector<uint32_t> blockers(ids.begin(), ids.begin() + round % 5);
      w.add(s, r, blockers);
      std::ostringstream line;
      line << s << ' ' << r << ' ' << blockers.size();
      for (uint32_t b : blockers) line << ' ' << b;
      expected += line.str() + '\n';
    }
    w.close();
  }
  const std::string text = test::readFile(dir / "d.txt");
  const size_t body = text.find("\n", text.find("\n") + 1) + 1;  // after the two comment lines
  EXPECT_EQ(text.substr(body), expected);
}

TEST(VisibilityTxtWriter, UnwritablePathIsAnInputError) {
  const auto dir = test::scratchDir();
  EXPECT_THROW(VisibilityTxtWriter((dir / "missing" / "v.txt").string()), InputError);
}

/// Interactions from the sink, and how the sink was called.
struct Sunk {
  std::vector<Interaction> interactions;
  size_t calls = 0;
  size_t splitSources = 0;  ///< calls whose first pair's source continued the previous call's
};

VisibilityGraph computeWithSink(const Scene& scene, const Subdivision& sub, int threads,
                                Sunk& sunk) {
  PropagationOptions o;
  o.threads = threads;
  o.interactionSink = [&sunk](const BlockerLists& lists) {
    ++sunk.calls;
    if (!lists.empty() && !sunk.interactions.empty() && sunk.interactions.back().s == lists.s(0))
      ++sunk.splitSources;
    for (size_t k = 0; k < lists.size(); ++k) {
      const auto ids = lists.blockers(k);
      sunk.interactions.push_back({lists.s(k), lists.r(k), {ids.begin(), ids.end()}});
    }
  };
  return computeVisibility(scene, sub, o);
}

void expectSameGraph(const std::vector<Interaction>& got, const std::vector<Interaction>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].s, want[i].s) << i;
    ASSERT_EQ(got[i].r, want[i].r) << i;
    ASSERT_EQ(got[i].blockers, want[i].blockers) << i;
  }
}

void expectSameStats(const VisibilityStats& a, const VisibilityStats& b) {
  EXPECT_EQ(a.pairsVisible, b.pairsVisible);
  EXPECT_EQ(a.pairsPartial, b.pairsPartial);
  EXPECT_EQ(a.sameCellShortcuts, b.sameCellShortcuts);
  EXPECT_EQ(a.meanBlockersPerPartial, b.meanBlockersPerPartial);
  EXPECT_EQ(a.meanShaftCullPerPartial, b.meanShaftCullPerPartial);
  EXPECT_EQ(a.shaftSamples, b.shaftSamples);
  EXPECT_EQ(a.patchStabbingTests, b.patchStabbingTests);
}

// An office wide enough that its floor slab sees more patches than a pipeline chunk holds, so
// that one source's pairs are handed on in several pieces.
TEST(PropagationSink, SameInteractionsAsTheGraphInOrderOnOneAndTwoThreads) {
  OfficeOptions oo;
  oo.rows = 3;
  oo.columns = 8;
  const Scene scene = generateOffice(oo);
  BspOptions bsp;
  bsp.minCoverage = kVisibilityMinCoverage;  // vis's cells (the default splits far more)
  const Subdivision sub = buildSubdivision(scene, bsp);
  PropagationOptions plainOptions;
  plainOptions.threads = 1;
  const VisibilityGraph plain = computeVisibility(scene, sub, plainOptions);
  ASSERT_GT(plain.stats.pairsPartial, 0u);
  for (size_t i = 1; i < plain.interactions.size(); ++i) {
    const Interaction& a = plain.interactions[i - 1];
    const Interaction& b = plain.interactions[i];
    ASSERT_TRUE(a.s < b.s || (a.s == b.s && a.r < b.r)) << i;
  }
  for (int threads : {1, 2}) {
    Sunk sunk;
    const VisibilityGraph g = computeWithSink(scene, sub, threads, sunk);
    EXPECT_TRUE(g.interactions.empty());  // handed to the sink, not held
    expectSameGraph(sunk.interactions, plain.interactions);
    expectSameStats(g.stats, plain.stats);
    EXPECT_GT(sunk.calls, 1u);
    EXPECT_GT(sunk.splitSources, 0u) << "no source was cut into pieces: the test lost its point";
  }
}

TEST(PropagationSink, MazeSameAsTheGraph) {
  MazeOptions m;
  m.width = 4;
  m.height = 3;
  m.seed = 3;
  const Scene scene = generateMaze(m);
  const Subdivision sub = buildSubdivision(scene);
  const VisibilityGraph plain = computeVisibility(scene, sub);
  Sunk sunk;
  const VisibilityGraph g = computeWithSink(scene, sub, 2, sunk);
  expectSameGraph(sunk.interactions, plain.interactions);
  expectSameStats(g.stats, plain.stats);
}

// `globalvis vis` streams visibility.txt: byte for byte what writeVisibilityTxt makes of the
// in-memory graph of the same scene and cells, with no temporary file left behind.
TEST(PropagationSink, VisCommandWritesTheInMemoryGraphsFile) {
  const auto dir = test::scratchDir();
  OfficeOptions oo;
  oo.rows = 2;
  oo.columns = 5;
  const std::string obj = (dir / "office.obj").string();
  writeObj(generateOffice(oo), obj);
  const auto r = test::runCli("vis '" + obj + "' -o '" + (dir / "out").string() + "' --threads 2");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "visibility.txt.part"));

  const Scene scene = removeHiddenFaces(loadScene(obj));  // what vis reads by default
  BspOptions bsp;
  bsp.minCoverage = kVisibilityMinCoverage;  // vis's default
  const VisibilityGraph g = computeVisibility(scene, buildSubdivision(scene, bsp));
  writeVisibilityTxt(g, (dir / "memory.txt").string());
  const std::string streamed = test::readFile(dir / "out" / "visibility.txt");
  EXPECT_GT(streamed.size(), 1000u);
  EXPECT_TRUE(streamed == test::readFile(dir / "memory.txt"));
}

}  // namespace
}  // namespace gv
