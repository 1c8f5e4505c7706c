// "Might see" sets: for each portal and direction of travel, a superset of the cells a sightline
// can reach after crossing it (the idea of Quake `vis`'s base pass, paper §4.1's pruning in
// spirit). The searches stop as soon as nothing new can be reached — they enumerate portal
// sequences, whose number explodes in open space, so this pruning is what makes them fast.
#pragma once

#include <cstdint>
#include <vector>

#include "bsp/subdivision.h"

namespace gv {

/// A fixed-size set of cells.
class CellSet {
 public:
  CellSet() = default;
  explicit CellSet(size_t n, bool full = false)
      : words_((n + 63) / 64, full ? ~uint64_t{0} : 0), size_(n) {
    if (full && n % 64) words_.back() = (uint64_t{1} << (n % 64)) - 1;
  }
  void insert(size_t i) { words_[i >> 6] |= uint64_t{1} << (i & 63); }
  void erase(size_t i) { words_[i >> 6] &= ~(uint64_t{1} << (i & 63)); }
  bool contains(size_t i) const { return (words_[i >> 6] >> (i & 63)) & 1; }
  /// this := a ∩ b
  void assignIntersection(const CellSet& a, const CellSet& b) {
    words_.resize(a.words_.size());
    size_ = a.size_;
    for (size_t w = 0; w < words_.size(); ++w) words_[w] = a.words_[w] & b.words_[w];
  }
  /// Whether this and `other` share an element.
  bool intersects(const CellSet& other) const {
    for (size_t w = 0; w < words_.size(); ++w)
      if (words_[w] & other.words_[w]) return true;
    return false;
  }
  size_t size() const { return size_; }

 private:
  std::vector<uint64_t> words_;
  size_t size_ = 0;
};

/// For portal p crossed into p.front (`intoFront`) or into p.back: the cells a line crossing it
/// that way may reach next. A cell is included when a chain of portals leads to it on which every
/// portal Q passes two necessary tests for a line that crossed P earlier: some vertex of Q is not
/// behind P's plane (the line moves away from P's plane after crossing it) and some vertex of P is
/// not in front of Q's plane (P lies before Q along the line). Any real continuation passes both,
/// so the set is a superset (with a tolerance, never tighter than exact).
class MightSee {
 public:
  /// Computes the sets; above `maxCells` cells (memory is portals × cells bits) it stores nothing
  /// and every query answers "all cells".
  MightSee(const Subdivision& sub, const Tolerance& tol, size_t maxCells = 40000);
  const CellSet& through(uint32_t portal, bool intoFront) const {
    return sets_.empty() ? all_ : sets_[2 * portal + (intoFront ? 1 : 0)];
  }
  bool enabled() const { return !sets_.empty(); }

 private:
  std::vector<CellSet> sets_;
  CellSet all_;
};

}  // namespace gv
