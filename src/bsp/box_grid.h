// A uniform grid over 2D boxes for "which boxes overlap this one" queries: keeps the portal
// construction free of all-pairs loops over a plane's faces and patches. Paper §3.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace gv {

/// A closed axis-aligned rectangle in some plane's 2D coordinates.
struct Box2 {
  double u0 = 0, v0 = 0, u1 = 0, v1 = 0;
  bool overlaps(const Box2& o) const {
    return u0 <= o.u1 && o.u0 <= u1 && v0 <= o.v1 && o.v0 <= v1;
  }
};

/// The boxes bucketed into about one grid cell per box (at most 256 x 256). A box is listed in
/// every grid cell it touches; a query visits each overlapping box once.
class BoxGrid2 {
 public:
  explicit BoxGrid2(std::vector<Box2> boxes) : boxes_(std::move(boxes)), stamp_(boxes_.size(), 0) {
    if (boxes_.empty()) return;
    Box2 all = boxes_.front();
    for (const Box2& b : boxes_) {
      all.u0 = std::min(all.u0, b.u0), all.v0 = std::min(all.v0, b.v0);
      all.u1 = std::max(all.u1, b.u1), all.v1 = std::max(all.v1, b.v1);
    }
    bounds_ = all;
    const int side =
        std::clamp(static_cast<int>(std::sqrt(static_cast<double>(boxes_.size()))), 1, 256);
    nu_ = nv_ = side;
    cellU_ = std::max((all.u1 - all.u0) / side, 1e-300);
    cellV_ = std::max((all.v1 - all.v0) / side, 1e-300);
    cells_.resize(static_cast<size_t>(nu_ * nv_));
    for (uint32_t i = 0; i < boxes_.size(); ++i) {
      const auto [iu0, iv0, iu1, iv1] = range(boxes_[i]);
      for (int iu = iu0; iu <= iu1; ++iu) {
        for (int iv = iv0; iv <= iv1; ++iv) cells_[static_cast<size_t>(iu * nv_ + iv)].push_back(i);
      }
    }
  }

  const Box2& box(uint32_t i) const { return boxes_[i]; }

  /// Calls visit(i) for each box i overlapping q, once each. Not reentrant.
  template <class Visit>
  void query(const Box2& q, Visit&& visit) {
    if (boxes_.empty() || !q.overlaps(bounds_)) return;
    ++epoch_;
    const auto [iu0, iv0, iu1, iv1] = range(q);
    for (int iu = iu0; iu <= iu1; ++iu) {
      for (int iv = iv0; iv <= iv1; ++iv) {
        for (uint32_t i : cells_[static_cast<size_t>(iu * nv_ + iv)]) {
          if (stamp_[i] == epoch_ || !boxes_[i].overlaps(q)) continue;
          stamp_[i] = epoch_;
          visit(i);
        }
      }
    }
  }

 private:
  struct Range {
    int iu0, iv0, iu1, iv1;
  };
  Range range(const Box2& b) const {
    // Clamp in floating point first: a cast of an out-of-range double to int is undefined.
    auto index = [](double t, int n) {
      return static_cast<int>(std::clamp(std::floor(t), 0.0, static_cast<double>(n - 1)));
    };
    auto clampU = [&](double u) { return index((u - bounds_.u0) / cellU_, nu_); };
    auto clampV = [&](double v) { return index((v - bounds_.v0) / cellV_, nv_); };
    return {clampU(b.u0), clampV(b.v0), clampU(b.u1), clampV(b.v1)};
  }

  std::vector<Box2> boxes_;
  std::vector<uint32_t> stamp_;
  uint32_t epoch_ = 0;
  Box2 bounds_;
  int nu_ = 1, nv_ = 1;
  double cellU_ = 1, cellV_ = 1;
  std::vector<std::vector<uint32_t>> cells_;
};

}  // namespace gv
