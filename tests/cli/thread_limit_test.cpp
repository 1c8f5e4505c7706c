// `--threads N` limits the whole command (cli/thread_limit.h): oneTBB work started anywhere in the
// process while the limit is alive, outside any arena of the caller's, runs on at most N threads.
#include "cli/thread_limit.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <mutex>
#include <set>
#include <thread>

namespace gv::cli {
namespace {

/// The distinct threads a plain tbb::parallel_for (the default arena, as the pictures use) runs
/// on; each item sleeps so that an idle worker would steal some.
size_t threadsUsedByAPlainLoop() {
  std::mutex m;
  std::set<std::thread::id> seen;
  tbb::parallel_for(0, 64, [&](int) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const std::lock_guard<std::mutex> lock(m);
    seen.insert(std::this_thread::get_id());
  });
  return seen.size();
}

TEST(ThreadLimit, OneThreadMeansOneThreadForLoopsThatTakeNoThreadCount) {
  {
    const ThreadLimit limit(1);
    EXPECT_EQ(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism), 1u);
    EXPECT_EQ(threadsUsedByAPlainLoop(), 1u);
  }
  // Gone with the limit. (A machine with one core would see 1 either way.)
  if (std::thread::hardware_concurrency() > 1) {
    EXPECT_GT(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism), 1u);
  }
}

TEST(ThreadLimit, ZeroLeavesEveryCore) {
  const size_t before =
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  const ThreadLimit limit(0);
  EXPECT_EQ(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism),
            before);
}

}  // namespace
}  // namespace gv::cli
