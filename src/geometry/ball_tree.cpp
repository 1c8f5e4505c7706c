// Building the ball hierarchy of ball_tree.h: median splits along the widest axis of the
// centres, nodes in preorder so that a walk needs no child pointers.
#include "geometry/ball_tree.h"

#include <algorithm>
#include <numeric>

namespace gv {

BallTree::BallTree(std::span<const Ball> balls, const Tolerance& tol, size_t leafSize) {
  if (balls.empty()) return;
  items_.resize(balls.size());
  std::iota(items_.begin(), items_.end(), 0u);
  nodes_.reserve(2 * balls.size() / std::max<size_t>(leafSize, 1) + 1);
  build(balls, 0, static_cast<uint32_t>(balls.size()), tol, std::max<size_t>(leafSize, 1));
}

uint32_t BallTree::build(std::span<const Ball> balls, uint32_t begin, uint32_t end,
                         const Tolerance& tol, size_t leafSize) {
  const auto index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  std::vector<Ball> inside;
  inside.reserve(end - begin);
  Vec3 lo = balls[items_[begin]].center, hi = lo;
  for (uint32_t k = begin; k < end; ++k) {
    const Ball& b = balls[items_[k]];
    inside.push_back(b);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], b.center[a]);
      hi[a] = std::max(hi[a], b.center[a]);
    }
  }
  nodes_[index].ball = ballAroundBalls(inside, tol);
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  if (end - begin <= leafSize) {
    nodes_[index].leaf = true;
  } else {
    const Vec3 extent = hi - lo;
    const int axis = extent[0] >= extent[1] && extent[0] >= extent[2] ? 0
                     : extent[1] >= extent[2]                         ? 1
                                                                      : 2;
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                     [&](uint32_t x, uint32_t y) {
                       return balls[x].center[axis] < balls[y].center[axis] ||
                              (balls[x].center[axis] == balls[y].center[axis] && x < y);
                     });
    build(balls, begin, mid, tol, leafSize);
    build(balls, mid, end, tol, leafSize);
  }
  nodes_[index].skip = static_cast<uint32_t>(nodes_.size());
  return index;
}

}  // namespace gv
