// Seidel's randomized incremental linear programming in a handful of dimensions: the feasibility
// engine behind stabbing-line tests (paper §4.1, after [Teller 1992], which uses the same tool).
// Small dense problems (<= 8 variables, tens of constraints) solved many thousands of times per
// second, incrementally as a depth-first search pushes and pops constraints.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace gv {

/// Largest number of variables the solver handles.
inline constexpr int kLpMaxDim = 8;

/// A point or coefficient vector; only the first `dim` entries of a problem are used.
using LpVector = std::array<double, kLpMaxDim>;

/// The halfspace a·x <= b. Callers scale rows to unit length so that violations are comparable.
struct LpConstraint {
  LpVector a{};
  double b = 0;
};

/// Maximises c·x subject to lo <= x <= hi (a box, which keeps every subproblem bounded) and a list
/// of halfspaces. Seidel's algorithm: keep the optimum of the constraints seen so far; when the
/// next constraint is violated, the new optimum lies on its hyperplane, found by a recursive
/// problem one dimension lower. Expected O(d! n) time; constraints are visited in a
/// deterministically shuffled order within each recursion, so results are reproducible.
/// One instance owns scratch memory and is not thread safe; use one per thread.
class SeidelLp {
 public:
  /// The optimum of the whole problem, or nullopt when it is infeasible (beyond rounding noise,
  /// kLpRelativeFeasibility). With ties, some optimal point.
  std::optional<LpVector> solve(int dim, std::span<const LpConstraint> constraints,
                                const LpVector& c, const LpVector& lo, const LpVector& hi);

  /// Incremental form: `x` is an optimum for constraints[0, first) (and the box); returns an
  /// optimum for all of them, doing work only for the new constraints that `x` violates.
  std::optional<LpVector> extend(int dim, std::span<const LpConstraint> constraints, size_t first,
                                 const LpVector& x, const LpVector& c, const LpVector& lo,
                                 const LpVector& hi);

 private:
  std::optional<LpVector> run(int dim, std::span<const LpConstraint> constraints, size_t first,
                              LpVector x, const LpVector& c, const LpVector& lo, const LpVector& hi,
                              int level);
  std::optional<LpVector> onHyperplane(int dim, std::span<const LpConstraint> constraints, size_t i,
                                       const LpVector& c, const LpVector& lo, const LpVector& hi,
                                       int level);
  std::vector<LpConstraint>& scratch(int level);

  std::vector<std::vector<LpConstraint>> scratch_;
  uint64_t rng_ = 0x9e3779b97f4a7c15ULL;
};

/// The vertex of the box lo <= x <= hi that maximises c·x (lo where c_j <= 0).
LpVector boxOptimum(int dim, const LpVector& c, const LpVector& lo, const LpVector& hi);

}  // namespace gv
