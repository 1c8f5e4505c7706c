// A bounding-ball hierarchy over a set of items given by their balls: a query that rejects
// whole groups by one ball test visits the items of the groups it keeps. The over-budget answer
// of the patch searches tests every unseen piece of a cell against a sequence's planes; in the
// large merged cells of sector levels (a hundred pieces and more) nearly all of them fail, and
// testing them one by one was about a sixth of `vis` on doom-fd1-e3m4 (10^9 tests).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/ball.h"
#include "geometry/tolerance.h"

namespace gv {

class BallTree {
 public:
  BallTree() = default;
  /// A tree over items 0..balls.size()-1 (item i held by balls[i]); leaves hold at most
  /// `leafSize` items. Split at the median of the centres along their widest axis.
  BallTree(std::span<const Ball> balls, const Tolerance& tol, size_t leafSize = 4);

  /// The ball holding every item (the zero ball when there are none).
  const Ball& bounds() const { return nodes_.empty() ? kEmpty : nodes_.front().ball; }

  /// The items in the tree's order: every node holds a run of it (ItemRange).
  std::span<const uint32_t> order() const { return items_; }
  /// The positions in order() of a node's items.
  struct ItemRange {
    uint32_t begin = 0, end = 0;
  };

  /// Calls visit(i, state) for every item i in a leaf whose ball and every enclosing ball
  /// `keep(ball, range, state)` accepts (range: the node's items, so that a caller can skip
  /// groups it has nothing to look for in); a ball it rejects skips all the items inside it.
  /// `state` starts as `root` and flows down: each child starts from its parent's state as keep
  /// left it (a plane test drops the planes a ball is wholly in front of, for everything inside
  /// it). Items are visited in the tree's order, not by index.
  template <class State, class Keep, class Visit>
  void forEachKept(State root, Keep&& keep, Visit&& visit) const {
    auto every = [&](uint32_t item, const State& state) {
      visit(item, state);
      return false;
    };
    if (!nodes_.empty()) walk(0, root, keep, every);
  }

  /// As forEachKept, but stops at the first item i for which accept(i, state) is true, and
  /// says whether there was one.
  template <class State, class Keep, class Accept>
  bool findKept(State root, Keep&& keep, Accept&& accept) const {
    return !nodes_.empty() && walk(0, root, keep, accept);
  }

 private:
  struct Node {
    Ball ball;
    uint32_t begin = 0, end = 0;  // items_[begin, end) lie inside
    uint32_t skip = 0;            // the next node after this subtree (preorder)
    bool leaf = false;
  };
  // True when `accept` took an item (the walk stops there).
  template <class State, class Keep, class Accept>
  bool walk(uint32_t i, State state, Keep& keep, Accept& accept) const {
    const Node& n = nodes_[i];
    if (!keep(n.ball, ItemRange{n.begin, n.end}, state)) return false;
    if (n.leaf) {
      for (uint32_t k = n.begin; k < n.end; ++k)
        if (accept(items_[k], state)) return true;
      return false;
    }
    // The first child follows its parent (preorder).
    return walk(i + 1, state, keep, accept) || walk(nodes_[i + 1].skip, state, keep, accept);
  }
  uint32_t build(std::span<const Ball> balls, uint32_t begin, uint32_t end, const Tolerance& tol,
                 size_t leafSize);

  static constexpr Ball kEmpty{};
  std::vector<Node> nodes_;      // preorder
  std::vector<uint32_t> items_;  // item indices, grouped by leaf
};

}  // namespace gv
