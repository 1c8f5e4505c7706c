// Dense dual simplex with box bounds and a re-checked Lagrangian bound (stabbing LP, paper §4.1).
// See dual_simplex.h.
#include "visibility/dual_simplex.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "geometry/tolerance.h"

namespace gv {
namespace {

// Below this magnitude a pivot element is taken as zero: the basis is (numerically) singular.
constexpr double kSingularPivot = 1e-12;
// Ratio-test entries below this are not pivoted on (they would blow the basis up).
constexpr double kRatioEpsilon = 1e-12;
// Pivots with an entry below this, or more than this many in a row, re-invert the basis instead
// of updating its inverse.
constexpr double kRefactorPivot = 1e-6;
constexpr int kMaxRankOneUpdates = 8;
// Multipliers may step this far below zero in the ratio test (Harris) to pivot on a larger entry.
constexpr double kHarrisSlack = 1e-11;

struct Row {
  LpVector a{};
  double b = 0;
};

Row rowOf(int32_t id, std::span<const LpConstraint> rows, const LpVector& lo, const LpVector& hi) {
  Row r;
  if (id >= 0) {
    r.a = rows[static_cast<size_t>(id)].a;
    r.b = rows[static_cast<size_t>(id)].b;
  } else if (id >= -kLpMaxDim) {
    const int j = -1 - id;
    r.a[j] = 1;
    r.b = hi[j];
  } else {
    const int j = -1 - kLpMaxDim - id;
    r.a[j] = -1;
    r.b = -lo[j];
  }
  return r;
}

SimplexBasis boxBasis(int dim, const LpVector& c) {
  SimplexBasis b;
  for (int j = 0; j < dim; ++j) b.tight[j] = c[j] > 0 ? -1 - j : -1 - kLpMaxDim - j;
  b.known = true;
  return b;
}

// Inverse of the dim x dim matrix m (rows = tight constraints) by Gauss–Jordan elimination with
// partial pivoting; false when singular.
bool invert(int dim, std::array<LpVector, kLpMaxDim> m, std::array<LpVector, kLpMaxDim>& inv) {
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) inv[i][j] = i == j ? 1 : 0;
  for (int col = 0; col < dim; ++col) {
    int p = col;
    for (int r = col + 1; r < dim; ++r)
      if (std::abs(m[r][col]) > std::abs(m[p][col])) p = r;
    if (!(std::abs(m[p][col]) > kSingularPivot)) return false;
    std::swap(m[p], m[col]);
    std::swap(inv[p], inv[col]);
    const double s = 1.0 / m[col][col];
    for (int j = 0; j < dim; ++j) m[col][j] *= s, inv[col][j] *= s;
    for (int r = 0; r < dim; ++r) {
      if (r == col || m[r][col] == 0) continue;
      const double f = m[r][col];
      for (int j = 0; j < dim; ++j) m[r][j] -= f * m[col][j], inv[r][j] -= f * inv[col][j];
    }
  }
  return true;
}

bool inBasis(const SimplexBasis& b, int dim, int32_t id) {
  for (int k = 0; k < dim; ++k)
    if (b.tight[k] == id) return true;
  return false;
}

// The Lagrangian bound of the multipliers y (on the tight rows; box multipliers are implied).
double certifiedBound(int dim, const SimplexBasis& basis, const LpVector& y,
                      std::span<const LpConstraint> rows, const LpVector& c, const LpVector& lo,
                      const LpVector& hi) {
  LpVector r = c, absSum{};
  double value = 0, allowance = 0;
  for (int j = 0; j < dim; ++j) absSum[j] = std::abs(c[j]);
  for (int k = 0; k < dim; ++k) {
    const int32_t id = basis.tight[k];
    if (id < 0) continue;
    const double yk = std::max(0.0, y[k]);
    if (yk == 0) continue;
    const LpConstraint& row = rows[static_cast<size_t>(id)];
    value += yk * row.b;
    allowance += std::abs(yk * row.b);
    for (int j = 0; j < dim; ++j) {
      r[j] -= yk * row.a[j];
      absSum[j] += std::abs(yk * row.a[j]);
    }
  }
  for (int j = 0; j < dim; ++j) {
    value += std::max(r[j] * lo[j], r[j] * hi[j]);
    allowance += absSum[j] * std::max(std::abs(lo[j]), std::abs(hi[j]));
  }
  // Every term above is a sum of at most ~2·dim rounded products: 16 ulps of the magnitudes
  // involved bound the rounding of the whole evaluation.
  return value + 16 * DBL_EPSILON * allowance;
}

}  // namespace

SimplexResult maximizeDualSimplex(int dim, std::span<const LpConstraint> rows, const LpVector& c,
                                  const LpVector& lo, const LpVector& hi,
                                  const SimplexBasis& warm) {
  SimplexResult result;
  SimplexBasis basis = warm;
  bool fromWarm = warm.known;
  if (fromWarm) {
    for (int k = 0; k < dim; ++k)
      if (basis.tight[k] >= static_cast<int32_t>(rows.size())) fromWarm = false;
  }
  if (!fromWarm) basis = boxBasis(dim, c);
  const int maxPivots = 50 + 4 * static_cast<int>(rows.size() + 2 * static_cast<size_t>(dim));
  std::array<LpVector, kLpMaxDim> m{}, inv{};
  LpVector q{}, x{}, y{}, w{};
  bool factored = false;
  int updates = 0;  // rank-one updates since the last inversion
  for (int iter = 0;; ++iter) {
    if (iter > maxPivots) return result;  // Failed: cycling or stalling
    if (!factored) {
      for (int k = 0; k < dim; ++k) {
        const Row r = rowOf(basis.tight[k], rows, lo, hi);
        m[k] = r.a;
        q[k] = r.b;
      }
      if (!invert(dim, m, inv)) {
        if (!fromWarm) return result;
        basis = boxBasis(dim, c);  // a stale warm start: begin again from the box
        fromWarm = false;
        continue;
      }
      factored = true;
      updates = 0;
    }
    double size = 1;
    for (int j = 0; j < dim; ++j) {
      x[j] = 0;
      for (int k = 0; k < dim; ++k) x[j] += inv[j][k] * q[k];
      size = std::max(size, std::abs(x[j]));
    }
    for (int k = 0; k < dim; ++k) {
      y[k] = 0;
      for (int j = 0; j < dim; ++j) y[k] += c[j] * inv[j][k];
    }
    // Entering constraint: the most violated one (rows are unit-scaled, like the box's).
    const double tolerance = kLpRelativeFeasibility * (1 + size);
    double worst = tolerance;
    int32_t entering = 0;
    bool found = false;
    for (size_t i = 0; i < rows.size(); ++i) {
      double v = -rows[i].b;
      for (int j = 0; j < dim; ++j) v += rows[i].a[j] * x[j];
      if (v > worst && !inBasis(basis, dim, static_cast<int32_t>(i))) {
        worst = v, entering = static_cast<int32_t>(i), found = true;
      }
    }
    for (int j = 0; j < dim; ++j) {
      if (x[j] - hi[j] > worst && !inBasis(basis, dim, -1 - j))
        worst = x[j] - hi[j], entering = -1 - j, found = true;
      if (lo[j] - x[j] > worst && !inBasis(basis, dim, -1 - kLpMaxDim - j))
        worst = lo[j] - x[j], entering = -1 - kLpMaxDim - j, found = true;
    }
    if (!found) {
      result.status = SimplexResult::Status::Optimal;
      result.x = x;
      result.basis = basis;
      result.certifiedUpperBound = certifiedBound(dim, basis, y, rows, c, lo, hi);
      result.pivots = iter;
      return result;
    }
    // Ratio test: y_B − θ w stays >= 0, w = a_enteringᵀ B⁻¹.
    const Row e = rowOf(entering, rows, lo, hi);
    // Harris's two passes: the largest step any candidate allows with its multiplier relaxed by
    // kHarrisSlack, then among the candidates within that step the largest pivot entry (a
    // larger entry keeps the next basis well conditioned; a multiplier that goes slightly
    // negative is clamped to 0 by the bound's check, which stays valid for any y >= 0).
    double limit = INFINITY;
    for (int k = 0; k < dim; ++k) {
      w[k] = 0;
      for (int j = 0; j < dim; ++j) w[k] += e.a[j] * inv[j][k];
      if (w[k] > kRatioEpsilon)
        limit = std::min(limit, (std::max(0.0, y[k]) + kHarrisSlack) / w[k]);
    }
    int leave = -1;
    double bestW = 0;
    for (int k = 0; k < dim; ++k) {
      if (!(w[k] > kRatioEpsilon) || std::max(0.0, y[k]) / w[k] > limit) continue;
      if (w[k] > bestW) bestW = w[k], leave = k;
    }
    if (leave < 0) return result;  // dual unbounded: rows infeasible (not expected here)
    basis.tight[leave] = entering;
    // The new inverse by a rank-one (Sherman–Morrison) update: row `leave` of the basis becomes
    // e.a, and wᵀ = e.aᵀ B⁻¹, so B'⁻¹ = B⁻¹ − B⁻¹[:, leave] (w − e_leave)ᵀ / w_leave. Re-inverted
    // from scratch every few pivots or after a small pivot, to keep rounding from piling up
    // (only x's accuracy depends on it: "blocked" rests on the re-checked bound alone).
    if (++updates > kMaxRankOneUpdates || w[leave] < kRefactorPivot) {
      factored = false;
      continue;
    }
    q[leave] = e.b;
    LpVector col{};
    for (int j = 0; j < dim; ++j) col[j] = inv[j][leave] / w[leave];
    w[leave] -= 1;
    for (int j = 0; j < dim; ++j)
      for (int k = 0; k < dim; ++k) inv[j][k] -= col[j] * w[k];
  }
}

}  // namespace gv
