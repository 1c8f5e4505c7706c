// The stderr progress bar: its line, its throttling, silence when disabled; the FNV-1a hash and
// the marked-section rewrite `bench` uses.
#include "util/progress_bar.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <thread>

#include "util/fnv_hash.h"
#include "util/marked_section.h"

namespace gv {
namespace {

/// What the bar wrote into a temporary file.
std::string contents(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  return out;
}

size_t count(const std::string& s, char c) {
  return static_cast<size_t>(std::count(s.begin(), s.end(), c));
}

TEST(ProgressBarTest, LineShowsPercentElapsedAndEta) {
  const std::string half = progressLine("BSP", 0.5, 2.0);
  EXPECT_NE(half.find("BSP ["), std::string::npos) << half;
  EXPECT_NE(half.find(" 50.0 %"), std::string::npos) << half;
  EXPECT_NE(half.find("2.0 s"), std::string::npos) << half;
  EXPECT_NE(half.find("ETA 2.0 s"), std::string::npos) << half;  // linear: as long again
  EXPECT_EQ(count(half, '#'), size_t(kProgressBarWidth / 2));
  // No ETA before anything is done or once all is; fractions out of range are clamped.
  EXPECT_EQ(progressLine("x", 0, 1).find("ETA"), std::string::npos);
  EXPECT_EQ(progressLine("x", 1, 1).find("ETA"), std::string::npos);
  EXPECT_NE(progressLine("x", 7, 1).find("100.0 %"), std::string::npos);
  EXPECT_NE(progressLine("x", -1, 1).find("  0.0 %"), std::string::npos);
  EXPECT_NE(progressLine("x", 0.25, 3725).find("ETA 3:06:15"), std::string::npos)
      << progressLine("x", 0.25, 3725);
}

TEST(ProgressBarTest, DisabledWritesNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressBar bar("quiet", false, f);
    EXPECT_FALSE(bar.callback());
    for (size_t i = 0; i <= 100; ++i) bar.update(i, 100);
    bar.note("a line");
    bar.finish();
  }
  EXPECT_EQ(contents(f), "");
  std::fclose(f);
}

TEST(ProgressBarTest, RedrawsAtMostTenTimesASecondAndEndsTheLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressBar bar("work", true, f, 0);
    auto cb = bar.callback();
    ASSERT_TRUE(cb);
    for (size_t i = 0; i < 100000; ++i) cb(i, 100000);  // far under 0.1 s
    cb(100000, 100000);
    cb(100000, 100000);  // after finishing: ignored
  }
  const std::string out = contents(f);
  // The first draw, then the final 100 %: two redraws, one newline.
  EXPECT_EQ(count(out, '\r'), 2u) << out;
  EXPECT_EQ(count(out, '\n'), 1u) << out;
  EXPECT_NE(out.find("100.0 %"), std::string::npos) << out;
  std::fclose(f);
}

TEST(ProgressBarTest, AStageShorterThanTheFirstDrawDelayShowsNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressBar bar("short", true, f);  // the default delay
    for (size_t i = 0; i <= 1000; ++i) bar.update(i, 1000);
    bar.note("a line is still printed");
  }
  EXPECT_EQ(contents(f), "a line is still printed\n");
  std::fclose(f);
}

TEST(ProgressBarTest, RedrawsAgainAfterTheInterval) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressBar bar("slow", true, f, 0);
    bar.update(1, 10);
    std::this_thread::sleep_for(std::chrono::duration<double>(kProgressRedrawSeconds * 1.5));
    bar.update(2, 10);
    EXPECT_EQ(count(contents(f), '\r'), 2u);
  }
  std::fclose(f);
}

TEST(ProgressBarTest, NoteGoesOnItsOwnLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressBar bar("n", true, f, 0);
    bar.update(0.5);
    bar.note("round 1 done");
  }
  const std::string out = contents(f);
  EXPECT_NE(out.find("\rround 1 done\n"), std::string::npos) << out;
  std::fclose(f);
}

TEST(Fnv1aTest, KnownVectors) {
  // Published FNV-1a 64 test values.
  Fnv1a empty;
  EXPECT_EQ(empty.value(), 0xcbf29ce484222325ull);
  Fnv1a a;
  a.text("a");
  EXPECT_EQ(a.value(), 0xaf63dc4c8601ec8cull);
  Fnv1a foobar;
  foobar.text("foobar");
  EXPECT_EQ(foobar.hex(), "85944171f73967e8");
  // Integers are fed as 8 bytes whatever their type.
  Fnv1a x, y;
  x.integer(uint32_t{7});
  y.integer(uint64_t{7});
  EXPECT_EQ(x.value(), y.value());
}

TEST(MarkedSectionTest, AppendsThenReplacesKeepingTheRest) {
  const std::string begin = "<!-- b -->", end = "<!-- e -->";
  const std::string doc = "# Title\n\ntext\n";
  const std::string once = replaceMarkedSection(doc, begin, end, "table 1");
  EXPECT_EQ(once, "# Title\n\ntext\n\n<!-- b -->\ntable 1\n<!-- e -->\n");
  const std::string edited = once + "after\n";
  const std::string twice = replaceMarkedSection(edited, begin, end, "table 2\n");
  EXPECT_EQ(twice, "# Title\n\ntext\n\n<!-- b -->\ntable 2\n<!-- e -->\nafter\n");
  // A lone begin marker is not a section: append a whole one.
  const std::string lone = replaceMarkedSection("x\n<!-- b -->\n", begin, end, "t");
  EXPECT_EQ(lone, "x\n<!-- b -->\n\n<!-- b -->\nt\n<!-- e -->\n");
  EXPECT_EQ(replaceMarkedSection("", begin, end, "t"), "<!-- b -->\nt\n<!-- e -->\n");
}

}  // namespace
}  // namespace gv
