// The dual simplex of the stabbing LP against Seidel's LP (an independent solver) on seeded random
// problems, its warm start, and the soundness of its certified bound (never below the true
// optimum, checked by sampling feasible points as well).
#include "visibility/dual_simplex.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "visibility/linear_program.h"

namespace gv {
namespace {

struct Problem {
  int dim = 0;
  std::vector<LpConstraint> rows;
  LpVector c{}, lo{}, hi{};
};

// Rows a·x <= b with unit a through points near the origin, so the origin side is feasible and
// the box keeps everything bounded.
Problem randomProblem(std::mt19937_64& rng, int dim, int rows) {
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(-1, 1);
  Problem p;
  p.dim = dim;
  for (int j = 0; j < dim; ++j) p.c[j] = g(rng), p.lo[j] = -10, p.hi[j] = 10;
  for (int i = 0; i < rows; ++i) {
    LpConstraint r;
    double n = 0;
    for (int j = 0; j < dim; ++j) r.a[j] = g(rng), n += r.a[j] * r.a[j];
    n = std::sqrt(n);
    for (int j = 0; j < dim; ++j) r.a[j] /= n;
    r.b = 1.5 + 2 * u(rng);  // some rows cut the origin off: infeasible problems occur too
    p.rows.push_back(r);
  }
  return p;
}

double value(const Problem& p, const LpVector& x) {
  double v = 0;
  for (int j = 0; j < p.dim; ++j) v += p.c[j] * x[j];
  return v;
}

TEST(DualSimplex, AgreesWithSeidelOnRandomProblems) {
  std::mt19937_64 rng(20261201);
  SeidelLp seidel;
  int feasible = 0, infeasible = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int dim = 2 + trial % 5;
    const Problem p = randomProblem(rng, dim, 4 + static_cast<int>(rng() % 60));
    const std::optional<LpVector> ref = seidel.solve(dim, p.rows, p.c, p.lo, p.hi);
    const SimplexResult r = maximizeDualSimplex(dim, p.rows, p.c, p.lo, p.hi, SimplexBasis{});
    if (!ref) {
      // Infeasible: the simplex must not claim an optimum.
      EXPECT_NE(r.status, SimplexResult::Status::Optimal) << "trial " << trial;
      ++infeasible;
      continue;
    }
    ++feasible;
    ASSERT_EQ(r.status, SimplexResult::Status::Optimal) << "trial " << trial;
    const double v = value(p, *ref);
    EXPECT_NEAR(value(p, r.x), v, 1e-7 * (1 + std::abs(v))) << "trial " << trial;
    // The certificate is an upper bound of the optimum, and a tight one.
    EXPECT_GE(r.certifiedUpperBound, v - 1e-9 * (1 + std::abs(v))) << "trial " << trial;
    EXPECT_LE(r.certifiedUpperBound, v + 1e-6 * (1 + std::abs(v))) << "trial " << trial;
  }
  // The generator is not trivial: both kinds occur often.
  EXPECT_GT(feasible, 100);
  EXPECT_GT(infeasible, 50);
}

TEST(DualSimplex, WarmStartFromAPrefixGivesTheSameOptimum) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int dim = 6;
    Problem p = randomProblem(rng, dim, 40);
    for (LpConstraint& r : p.rows) r.b = std::abs(r.b) + 0.5;  // feasible
    const std::span<const LpConstraint> prefix(p.rows.data(), 20);
    const SimplexResult first = maximizeDualSimplex(dim, prefix, p.c, p.lo, p.hi, SimplexBasis{});
    ASSERT_EQ(first.status, SimplexResult::Status::Optimal);
    const SimplexResult warm = maximizeDualSimplex(dim, p.rows, p.c, p.lo, p.hi, first.basis);
    const SimplexResult cold = maximizeDualSimplex(dim, p.rows, p.c, p.lo, p.hi, SimplexBasis{});
    ASSERT_EQ(warm.status, SimplexResult::Status::Optimal);
    ASSERT_EQ(cold.status, SimplexResult::Status::Optimal);
    EXPECT_NEAR(value(p, warm.x), value(p, cold.x), 1e-8 * (1 + std::abs(value(p, cold.x))));
  }
}

TEST(DualSimplex, CertifiedBoundHoldsAtSampledFeasiblePoints) {
  // Independent of both solvers: random points of the box that satisfy every row never beat the
  // certified bound.
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-10, 10);
  int checked = 0;
  for (int trial = 0; trial < 100; ++trial) {
    Problem p = randomProblem(rng, 3, 6);
    for (LpConstraint& r : p.rows) r.b = std::abs(r.b) * 3;
    const SimplexResult r = maximizeDualSimplex(3, p.rows, p.c, p.lo, p.hi, SimplexBasis{});
    ASSERT_EQ(r.status, SimplexResult::Status::Optimal);
    for (int k = 0; k < 2000; ++k) {
      LpVector x{};
      for (int j = 0; j < 3; ++j) x[j] = u(rng);
      bool ok = true;
      for (const LpConstraint& row : p.rows) {
        double s = 0;
        for (int j = 0; j < 3; ++j) s += row.a[j] * x[j];
        ok = ok && s <= row.b;
      }
      if (!ok) continue;
      ++checked;
      EXPECT_LE(value(p, x), r.certifiedUpperBound + 1e-12);
    }
  }
  EXPECT_GT(checked, 10000);
}

}  // namespace
}  // namespace gv
