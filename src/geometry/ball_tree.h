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

  /// Calls visit(i, state) for every item i in a leaf whose ball and every enclosing ball
  /// `keep(ball, state)` accepts; a ball it rejects skips all the items inside it. `state`
  /// starts as `root` and flows down: each child starts from its parent's state as keep left it
  /// (a plane test drops the planes a ball is wholly in front of, for everything inside it).
  /// Items are visited in the tree's order, not by index.
  template <class State, class Keep, class Visit>
  void forEachKept(State root, Keep&& keep, Visit&& visit) const {
    if (!nodes_.empty()) walk(0, root, keep, visit);
  }

 private:
  struct Node {
    Ball ball;
    uint32_t begin = 0, end = 0;  // items_[begin, end) lie inside
    uint32_t skip = 0;            // the next node after this subtree (preorder)
    bool leaf = false;
  };
  template <class State, class Keep, class Visit>
  void walk(uint32_t i, State state, Keep& keep, Visit& visit) const {
    const Node& n = nodes_[i];
    if (!keep(n.ball, state)) return;
    if (n.leaf) {
      for (uint32_t k = n.begin; k < n.end; ++k) visit(items_[k], state);
      return;
    }
    walk(i + 1, state, keep, visit);  // the first child follows its parent (preorder)
    walk(nodes_[i + 1].skip, state, keep, visit);
  }
  uint32_t build(std::span<const Ball> balls, uint32_t begin, uint32_t end, const Tolerance& tol,
                 size_t leafSize);

  static constexpr Ball kEmpty{};
  std::vector<Node> nodes_;      // preorder
  std::vector<uint32_t> items_;  // item indices, grouped by leaf
};

}  // namespace gv
