// `--threads N` as a limit on the whole command, not only on the loops that take a thread count:
// the pictures, Embree's BVH builds and any other oneTBB work of the process stay within N too,
// so that `--threads 1` is one thread (the two-core figures in docs/BENCHMARKS.md compare against
// it).
#pragma once

#include <tbb/global_control.h>

#include <cstddef>
#include <optional>

namespace gv::cli {

/// While alive, oneTBB runs at most `threads` threads in this process (0: no limit, all cores).
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads) {
    if (threads > 0)
      control_.emplace(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  }

 private:
  std::optional<tbb::global_control> control_;
};

}  // namespace gv::cli
