// A counting sort and an ordered filter that run in parallel and give exactly what their serial
// loops give. The radiosity solver rebuilds per-element lists of its links (who gathers what,
// which links end where) several times a round; walked serially, those passes over every link
// and sample kept the second core idle for about a second of the 10k office's solve
// (docs/BENCHMARKS.md, session 41).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "util/check.h"
#include "util/parallel_for.h"

namespace gv {

/// Items are cut into this many chunks (fewer when there are few items), a number that depends
/// on the item count only, so that the output does not depend on the thread count; 8 keeps a few
/// cores busy while the per-chunk counts (chunks × keys) stay small beside the lists themselves.
inline size_t orderedChunks(size_t items) {
  constexpr size_t kMaxChunks = 8, kMinItemsPerChunk = 4096;
  return std::clamp<size_t>(items / kMinItemsPerChunk, 1, kMaxChunks);
}

/// Sorts the entries of items [0, items) into buckets [0, keys), as a serial counting sort does:
/// bucket k is values[begin[k] .. begin[k + 1]), its entries in item order, and an item's in the
/// order it gives them. `entries(i, put)` calls put(key, value) for each entry of item i and must
/// give the same entries every time it is called (it is called twice per item: to count, then to
/// place). Runs on the current oneTBB arena.
template <typename Value, typename Entries>
void bucketInOrder(size_t items, size_t keys, Entries entries, std::vector<uint32_t>& begin,
                   std::vector<Value>& values) {
  const size_t chunks = orderedChunks(items);
  auto chunkItems = [&](size_t c) {
    return std::pair{items * c / chunks, items * (c + 1) / chunks};
  };
  // at[c * keys + k]: chunk c's count for bucket k, then where its next entry for k goes.
  std::vector<uint32_t> at(chunks * keys, 0);
  parallelForEach(chunks, [&](size_t c) {
    uint32_t* count = at.data() + c * keys;
    const auto [first, last] = chunkItems(c);
    for (size_t i = first; i < last; ++i)
      entries(i, [&](uint32_t key, const Value&) { ++count[key]; });
  });
  begin.assign(keys + 1, 0);
  parallelForEach(keys, [&](size_t k) {
    uint32_t total = 0;
    for (size_t c = 0; c < chunks; ++c) total += at[c * keys + k];
    begin[k + 1] = total;
  });
  uint64_t sum = 0;
  for (size_t k = 0; k < keys; ++k) {
    sum += begin[k + 1];
    CHECK_MSG(sum <= UINT32_MAX, "bucketInOrder: more than 2^32 entries");
    begin[k + 1] = static_cast<uint32_t>(sum);
  }
  parallelForEach(keys, [&](size_t k) {
    uint32_t next = begin[k];
    for (size_t c = 0; c < chunks; ++c) {
      const uint32_t count = at[c * keys + k];
      at[c * keys + k] = next;
      next += count;
    }
  });
  values.resize(begin[keys]);
  parallelForEach(chunks, [&](size_t c) {
    uint32_t* next = at.data() + c * keys;
    const auto [first, last] = chunkItems(c);
    for (size_t i = first; i < last; ++i)
      entries(i, [&](uint32_t key, const Value& v) { values[next[key]++] = v; });
  });
}

/// The values `entries(i, put)` puts for items [0, items), in item order, gathered in parallel:
/// what a serial loop pushing them into one vector gives.
template <typename Value, typename Entries>
std::vector<Value> collectInOrder(size_t items, Entries entries) {
  const size_t chunks = orderedChunks(items);
  std::vector<std::vector<Value>> parts(chunks);
  parallelForEach(chunks, [&](size_t c) {
    const size_t first = items * c / chunks, last = items * (c + 1) / chunks;
    for (size_t i = first; i < last; ++i)
      entries(i, [&](const Value& v) { parts[c].push_back(v); });
  });
  if (chunks == 1) return std::move(parts[0]);
  size_t total = 0;
  for (const auto& p : parts) total += p.size();
  std::vector<Value> out;
  out.reserve(total);
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

}  // namespace gv
