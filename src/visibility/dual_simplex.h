// A dense dual simplex for the stabbing LP (paper §4.1): a handful of variables in a box and a
// growing list of halfspaces, warm-started from the parent's basis as the portal-sequence search
// deepens. Its "infeasible beyond the margin" answers come with a Lagrangian certificate that is
// re-checked independently of the pivoting, so rounding in the solver can never prune a sequence
// that has a stabbing line.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include "visibility/linear_program.h"

namespace gv {

/// Which constraints are tight at a vertex: `dim` entries, each a row index (>= 0) or a box bound
/// (-1 - j: x_j <= hi_j; -1 - kLpMaxDim - j: x_j >= lo_j).
struct SimplexBasis {
  std::array<int32_t, kLpMaxDim> tight{};
  bool known = false;  ///< false: start from the box corner that maximises c
};

struct SimplexResult {
  enum class Status { Optimal, Failed };
  Status status = Status::Failed;
  LpVector x{};        ///< the optimal vertex (Optimal only)
  SimplexBasis basis;  ///< its tight constraints, a warm start for a superset of the rows
  /// A proven upper bound of max c·x over the box and the rows, from the final multipliers y >= 0
  /// alone: y·b + Σ_j max(r_j lo_j, r_j hi_j) with r = c − Aᵀy, plus a rounding allowance. Valid
  /// whatever the pivoting did; +inf when unknown.
  double certifiedUpperBound = INFINITY;
  int pivots = 0;
};

/// Maximises c·x subject to lo <= x <= hi and a·x <= b for every row (rows scaled to unit size),
/// by the dual simplex method: start from a dual-feasible basis (`warm` if known, else the box
/// corner maximising c), pivot in the most violated row until none is violated. `Failed` on a
/// singular basis or too many pivots (callers then use another method or stay conservative).
SimplexResult maximizeDualSimplex(int dim, std::span<const LpConstraint> rows, const LpVector& c,
                                  const LpVector& lo, const LpVector& hi, const SimplexBasis& warm);

}  // namespace gv
