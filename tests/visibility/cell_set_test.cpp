// Tests of CellSet, the bit set of cells the searches intersect on every step: set operations
// against a plain std::set on random contents across word boundaries.
#include "visibility/cell_set.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

namespace gv {
namespace {

std::vector<size_t> contents(const CellSet& s) {
  std::vector<size_t> out;
  s.forEach([&](size_t i) { out.push_back(i); });
  return out;
}

TEST(CellSet, OperationsMatchOrderedSets) {
  std::mt19937_64 rng(3);
  for (size_t n : {1u, 63u, 64u, 65u, 200u}) {
    std::bernoulli_distribution coin(0.4);
    CellSet a(n), b(n), seen(n);
    std::set<size_t> sa, sb, sseen;
    for (size_t i = 0; i < n; ++i) {
      if (coin(rng)) a.insert(i), sa.insert(i);
      if (coin(rng)) b.insert(i), sb.insert(i);
      if (coin(rng)) seen.insert(i), sseen.insert(i);
    }
    CellSet both(n);
    const bool fresh = both.assignIntersectionHasNew(a, b, seen);
    std::vector<size_t> inter, interNew;
    for (size_t i : sa)
      if (sb.count(i)) {
        inter.push_back(i);
        if (!sseen.count(i)) interNew.push_back(i);
      }
    EXPECT_EQ(contents(both), inter) << n;
    EXPECT_EQ(fresh, !interNew.empty()) << n;
    both.subtract(seen);
    EXPECT_EQ(contents(both), interNew) << n;
    EXPECT_EQ(both.count(), interNew.size()) << n;
    // In place: this := this ∩ b, as the target checks use it.
    CellSet self = a;
    self.assignIntersectionHasNew(self, b, seen);
    EXPECT_EQ(contents(self), inter) << n;
  }
}

}  // namespace
}  // namespace gv
