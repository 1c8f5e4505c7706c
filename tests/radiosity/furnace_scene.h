// Test scenes for hierarchical radiosity: closed boxes of inward-facing walls (the furnace, where
// B = E / (1 - ρ) exactly and every point's form factors sum to 1).
#pragma once

#include <gtest/gtest.h>

#include "generators/scene_builder.h"
#include "scene/scene.h"

namespace gv::testing {

/// Adds the six inward-facing faces of the box [lo, hi], each cut into n x n patches.
inline void addInwardBox(SceneBuilder& b, const Vec3& lo, const Vec3& hi, uint32_t material,
                         int n) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          Vec3 p0, p1;
          p0[axis] = p1[axis] = side == 0 ? lo[axis] : hi[axis];
          p0[u] = lo[u] + (hi[u] - lo[u]) * i / n;
          p1[u] = lo[u] + (hi[u] - lo[u]) * (i + 1) / n;
          p0[v] = lo[v] + (hi[v] - lo[v]) * j / n;
          p1[v] = lo[v] + (hi[v] - lo[v]) * (j + 1) / n;
          // Facing into the box: +axis on the low side, -axis on the high side.
          ASSERT_TRUE(b.addAxisRect(axis, side == 0, p0, p1, material));
        }
      }
    }
  }
}

}  // namespace gv::testing
