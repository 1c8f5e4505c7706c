// Parallel loops on oneTBB: one whose workers each keep their own state (search buffers,
// stabbers; the per-source searches of `vis` run on it), and a plain one (the radiosity solver's
// per-link and per-element loops).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cstddef>

namespace gv {

/// Runs fn(worker, index) for index in [0, n) on at most `threads` oneTBB workers, each with its
/// own state from makeWorker(); each index exactly once. Results land per index, so the output
/// does not depend on the schedule.
template <typename MakeWorker, typename Fn>
void parallelFor(size_t n, int threads, MakeWorker makeWorker, Fn fn) {
  using Worker = decltype(makeWorker());
  tbb::enumerable_thread_specific<Worker> workers(makeWorker);
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        Worker& w = workers.local();
                        for (size_t i = r.begin(); i < r.end(); ++i) fn(w, i);
                      });
  });
}

/// Runs fn(index) for index in [0, n) on the current oneTBB task arena (a caller bounds the
/// threads with its own tbb::task_arena), each index exactly once. For loops whose results land
/// per index: what they compute does not depend on the schedule.
template <typename Fn>
void parallelForEach(size_t n, Fn fn) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) fn(i);
  });
}

}  // namespace gv
