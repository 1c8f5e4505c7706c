// Interactions with their blocker lists (paper §5) packed in flat arrays: how propagation hands
// finished sources on without a heap block per pair (hundreds of millions of ids on big scenes).
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace gv {

/// Interactions (s, r) in the order added, each with its blocker list (empty = VISIBLE): list k
/// is ids[start[k], start[k + 1]). The compact form of a run of Interaction values.
class BlockerLists {
 public:
  /// Pairs held.
  size_t size() const { return pairs_.size(); }
  bool empty() const { return pairs_.empty(); }
  uint32_t s(size_t k) const { return pairs_[k].first; }
  uint32_t r(size_t k) const { return pairs_[k].second; }
  /// The blocker list of pair k, sorted as added.
  std::span<const uint32_t> blockers(size_t k) const {
    return {ids_.data() + start_[k], ids_.data() + start_[k + 1]};
  }
  /// Blocker ids held, over all pairs.
  size_t idCount() const { return ids_.size(); }
  /// Ids the id array can hold without growing.
  size_t idCapacity() const { return ids_.capacity(); }
  /// Appends pair (s, r) with `blockers`.
  void add(uint32_t s, uint32_t r, std::span<const uint32_t> blockers) {
    pairs_.emplace_back(s, r);
    ids_.insert(ids_.end(), blockers.begin(), blockers.end());
    start_.push_back(ids_.size());
  }
  /// Appends pair (s, r) with an empty list, which addBlocker then extends.
  void addPair(uint32_t s, uint32_t r) {
    pairs_.emplace_back(s, r);
    start_.push_back(ids_.size());
  }
  /// Appends `id` to the list of the last pair added.
  void addBlocker(uint32_t id) {
    ids_.push_back(id);
    ++start_.back();
  }
  /// Removes the last pair added and its blockers.
  void popPair() {
    pairs_.pop_back();
    start_.pop_back();
    ids_.resize(start_.back());
  }
  /// Removes every pair, keeping the capacity (a reused block allocates nothing).
  void clear() {
    pairs_.clear();
    ids_.clear();
    start_.assign(1, 0);
  }

 private:
  std::vector<std::pair<uint32_t, uint32_t>> pairs_;
  std::vector<uint64_t> start_{0};
  std::vector<uint32_t> ids_;
};

}  // namespace gv
