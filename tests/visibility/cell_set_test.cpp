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

// anyNotIn visits the members not in `seen` in ascending order, stops at the first the predicate
// accepts, and tolerates the predicate erasing members as it goes (the target checks drop cells).
TEST(CellSet, AnyNotInStopsAtTheFirstAcceptedAndAllowsErasing) {
  std::mt19937_64 rng(5);
  for (size_t n : {1u, 64u, 130u, 300u}) {
    std::bernoulli_distribution coin(0.5);
    CellSet a(n), seen(n);
    std::vector<size_t> expected;
    for (size_t i = 0; i < n; ++i) {
      const bool in = coin(rng), isSeen = coin(rng);
      if (in) a.insert(i);
      if (isSeen) seen.insert(i);
      if (in && !isSeen) expected.push_back(i);
    }
    std::vector<size_t> visited;
    EXPECT_FALSE(a.anyNotIn(seen, [&](size_t i) {
      visited.push_back(i);
      return false;
    }));
    EXPECT_EQ(visited, expected) << n;
    if (expected.empty()) continue;
    // Accept the middle one, erasing each rejected member: the rest stays.
    const size_t accept = expected[expected.size() / 2];
    CellSet b = a;
    visited.clear();
    EXPECT_TRUE(b.anyNotIn(seen, [&](size_t i) {
      visited.push_back(i);
      if (i == accept) return true;
      b.erase(i);
      return false;
    }));
    EXPECT_EQ(visited.back(), accept) << n;
    EXPECT_EQ(visited.size(), expected.size() / 2 + 1) << n;
    for (size_t i : expected) EXPECT_EQ(b.contains(i), i >= accept) << n << " " << i;
  }
}

}  // namespace
}  // namespace gv
