// A fixed-size set of cells, one bit each: the "visible" and "might see" sets of the portal
// searches (propagation over our cells, and the leaf PVS over Quake portal files).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

namespace gv {

class CellSet {
 public:
  CellSet() = default;
  /// n cells, all absent (or all present when `full`).
  explicit CellSet(size_t n, bool full = false) : words_((n + 63) / 64, full ? ~uint64_t{0} : 0) {
    if (full && n % 64) words_.back() = (uint64_t{1} << (n % 64)) - 1;
  }
  void insert(size_t i) { words_[i >> 6] |= uint64_t{1} << (i & 63); }
  void erase(size_t i) { words_[i >> 6] &= ~(uint64_t{1} << (i & 63)); }
  bool contains(size_t i) const { return (words_[i >> 6] >> (i & 63)) & 1; }
  void clear() { std::fill(words_.begin(), words_.end(), 0); }
  size_t count() const {
    size_t c = 0;
    for (uint64_t w : words_) c += static_cast<size_t>(std::popcount(w));
    return c;
  }
  /// this := this ∪ other (same size).
  void unite(const CellSet& other) {
    for (size_t w = 0; w < words_.size(); ++w) words_[w] |= other.words_[w];
  }
  /// this := this \ other (same size).
  void subtract(const CellSet& other) {
    for (size_t w = 0; w < words_.size(); ++w) words_[w] &= ~other.words_[w];
  }
  /// this := a ∩ b (same size).
  void assignIntersection(const CellSet& a, const CellSet& b) {
    words_.resize(a.words_.size());
    for (size_t w = 0; w < words_.size(); ++w) words_[w] = a.words_[w] & b.words_[w];
  }
  /// this := a ∩ b; returns whether the result holds a cell not in `seen`.
  bool assignIntersectionHasNew(const CellSet& a, const CellSet& b, const CellSet& seen) {
    words_.resize(a.words_.size());
    uint64_t fresh = 0;
    for (size_t w = 0; w < words_.size(); ++w) {
      words_[w] = a.words_[w] & b.words_[w];
      fresh |= words_[w] & ~seen.words_[w];
    }
    return fresh != 0;
  }
  /// Whether this and `other` share a cell.
  bool intersects(const CellSet& other) const {
    for (size_t w = 0; w < words_.size(); ++w)
      if (words_[w] & other.words_[w]) return true;
    return false;
  }
  /// this := the cells of [0, n) not in this.
  void complement(size_t n) {
    for (uint64_t& w : words_) w = ~w;
    if (n % 64 && !words_.empty()) words_.back() &= (uint64_t{1} << (n % 64)) - 1;
  }
  /// Calls f(i) for every cell i in the set, ascending.
  template <typename F>
  void forEach(F f) const {
    for (size_t w = 0; w < words_.size(); ++w)
      for (uint64_t bits = words_[w]; bits; bits &= bits - 1)
        f(w * 64 + static_cast<size_t>(std::countr_zero(bits)));
  }
  /// Whether f(i) holds for some cell i of this set not in `seen`: tries them in ascending order
  /// and stops at the first. f may erase cells from this set.
  template <typename F>
  bool anyNotIn(const CellSet& seen, F f) const {
    for (size_t w = 0; w < words_.size(); ++w)
      for (uint64_t bits = words_[w] & ~seen.words_[w]; bits; bits &= bits - 1)
        if (f(w * 64 + static_cast<size_t>(std::countr_zero(bits)))) return true;
    return false;
  }
  /// Capacity in cells, rounded up to whole words.
  size_t capacity() const { return words_.size() * 64; }

 private:
  std::vector<uint64_t> words_;
};

}  // namespace gv
