// bucketInOrder and collectInOrder against the serial loops they replace, on random entries of
// many sizes (one chunk, several, uneven), on 1 and 2 threads.
#include "util/ordered_buckets.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace gv {
namespace {

/// splitmix64: a cheap, well-mixed hash of (item, draw).
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

/// Item i's entries: 0-3 of them, keys and values drawn from a hash of i, so that every call
/// gives the same ones (as bucketInOrder requires).
template <typename Put>
void entriesOf(size_t i, size_t keys, Put put) {
  const int count = static_cast<int>(mix(i * 8) % 4);
  for (int k = 1; k <= count; ++k)
    put(static_cast<uint32_t>(mix(i * 8 + k) % keys),
        std::pair{static_cast<uint32_t>(i), static_cast<int>(mix(i * 8 + 4 + k) % 1000)});
}

using Entry = std::pair<uint32_t, int>;

/// The serial counting sort bucketInOrder stands for.
void serialBuckets(size_t items, size_t keys, std::vector<uint32_t>& begin,
                   std::vector<Entry>& values) {
  begin.assign(keys + 1, 0);
  for (size_t i = 0; i < items; ++i)
    entriesOf(i, keys, [&](uint32_t key, const Entry&) { ++begin[key + 1]; });
  for (size_t k = 0; k < keys; ++k) begin[k + 1] += begin[k];
  values.assign(begin[keys], {});
  std::vector<uint32_t> at(begin.begin(), begin.end() - 1);
  for (size_t i = 0; i < items; ++i)
    entriesOf(i, keys, [&](uint32_t key, const Entry& v) { values[at[key]++] = v; });
}

TEST(OrderedBuckets, BucketInOrderIsTheSerialCountingSort) {
  for (const int threads : {1, 2}) {
    tbb::task_arena arena(threads);
    for (const size_t items :
         {size_t{0}, size_t{1}, size_t{100}, size_t{4096}, size_t{9000}, size_t{50001}}) {
      for (const size_t keys : {size_t{1}, size_t{7}, size_t{1000}}) {
        std::vector<uint32_t> begin, wantBegin;
        std::vector<Entry> values, want;
        serialBuckets(items, keys, wantBegin, want);
        arena.execute([&] {
          bucketInOrder<Entry>(
              items, keys, [&](size_t i, auto put) { entriesOf(i, keys, put); }, begin, values);
        });
        EXPECT_EQ(begin, wantBegin) << items << " items, " << keys << " keys, " << threads;
        EXPECT_EQ(values, want) << items << " items, " << keys << " keys, " << threads;
      }
    }
  }
}

TEST(OrderedBuckets, CollectInOrderIsTheSerialFilter) {
  for (const int threads : {1, 2}) {
    tbb::task_arena arena(threads);
    for (const size_t items : {size_t{0}, size_t{3}, size_t{4095}, size_t{40000}}) {
      std::vector<Entry> want;
      for (size_t i = 0; i < items; ++i)
        entriesOf(i, 50, [&](uint32_t key, const Entry& v) {
          if (key % 3 != 0) want.push_back(v);
        });
      std::vector<Entry> got;
      arena.execute([&] {
        got = collectInOrder<Entry>(items, [&](size_t i, auto put) {
          entriesOf(i, 50, [&](uint32_t key, const Entry& v) {
            if (key % 3 != 0) put(v);
          });
        });
      });
      EXPECT_EQ(got, want) << items << " items, " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace gv
