// Seidel's randomized incremental LP (small dimension), used by the stabbing-line test (paper
// §4.1). See linear_program.h for the contract.
#include "visibility/linear_program.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/tolerance.h"

namespace gv {
namespace {

double dotN(int dim, const LpVector& a, const LpVector& x) {
  double s = 0;
  for (int j = 0; j < dim; ++j) s += a[j] * x[j];
  return s;
}

double maxAbs(int dim, const LpVector& x) {
  double m = 0;
  for (int j = 0; j < dim; ++j) m = std::max(m, std::abs(x[j]));
  return m;
}

// Rounding noise of a·x - b for a unit row at the point x.
double feasibilitySlack(int dim, const LpVector& x) {
  return kLpRelativeFeasibility * (1.0 + maxAbs(dim, x));
}

uint64_t splitmix(uint64_t& state) {
  uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

LpVector boxOptimum(int dim, const LpVector& c, const LpVector& lo, const LpVector& hi) {
  LpVector x{};
  for (int j = 0; j < dim; ++j) x[j] = c[j] > 0 ? hi[j] : lo[j];
  return x;
}

std::vector<LpConstraint>& SeidelLp::scratch(int level) {
  // Allocate every level at once so that no level's buffer moves while a shallower level's
  // rows are in use by the recursion.
  if (scratch_.size() < kLpMaxDim + 1) scratch_.resize(kLpMaxDim + 1);
  return scratch_[level];
}

std::optional<LpVector> SeidelLp::solve(int dim, std::span<const LpConstraint> constraints,
                                        const LpVector& c, const LpVector& lo, const LpVector& hi) {
  return extend(dim, constraints, 0, boxOptimum(dim, c, lo, hi), c, lo, hi);
}

std::optional<LpVector> SeidelLp::extend(int dim, std::span<const LpConstraint> constraints,
                                         size_t first, const LpVector& x, const LpVector& c,
                                         const LpVector& lo, const LpVector& hi) {
  if (dim < 1 || dim > kLpMaxDim) throw std::logic_error("SeidelLp: dimension out of range");
  // Reseed from the problem's shape so that the same problem gives the same answer in every
  // thread and run (the shuffles only affect speed and the choice among tied optima).
  rng_ = 0x2545f4914f6cdd1dULL ^ (constraints.size() * 0x9e3779b97f4a7c15ULL) ^ first;
  return run(dim, constraints, first, x, c, lo, hi, 0);
}

std::optional<LpVector> SeidelLp::run(int dim, std::span<const LpConstraint> constraints,
                                      size_t first, LpVector x, const LpVector& c,
                                      const LpVector& lo, const LpVector& hi, int level) {
  if (dim == 1) {
    // One variable: intersect the interval [lo, hi] with every constraint.
    double l = lo[0], h = hi[0];
    for (const LpConstraint& k : constraints) {
      if (k.a[0] > 0) {
        h = std::min(h, k.b / k.a[0]);
      } else if (k.a[0] < 0) {
        l = std::max(l, k.b / k.a[0]);
      } else if (k.b < -kLpRelativeFeasibility) {
        return std::nullopt;
      }
    }
    if (l > h + kLpRelativeFeasibility * (1.0 + std::max(std::abs(l), std::abs(h))))
      return std::nullopt;
    if (l > h) l = h = 0.5 * (l + h);  // touching within rounding: one point
    x[0] = c[0] > 0 ? h : l;
    return x;
  }
  for (size_t i = first; i < constraints.size(); ++i) {
    const LpConstraint& k = constraints[i];
    if (dotN(dim, k.a, x) <= k.b + feasibilitySlack(dim, x)) continue;
    std::optional<LpVector> y = onHyperplane(dim, constraints, i, c, lo, hi, level);
    if (!y) return std::nullopt;
    x = *y;
  }
  return x;
}

// The optimum over constraints[0, i), the box, and the hyperplane of constraints[i]: eliminate
// the variable with the largest coefficient in row i (the best-conditioned pivot), project every
// earlier row and the eliminated variable's two box sides into dim - 1 variables, solve, lift.
std::optional<LpVector> SeidelLp::onHyperplane(int dim, std::span<const LpConstraint> constraints,
                                               size_t i, const LpVector& c, const LpVector& lo,
                                               const LpVector& hi, int level) {
  const LpConstraint& h = constraints[i];
  int k = 0;
  for (int j = 1; j < dim; ++j)
    if (std::abs(h.a[j]) > std::abs(h.a[k])) k = j;
  const double pivot = h.a[k];
  if (std::abs(pivot) < 1e-300) {
    // A zero row that is violated: 0 <= b fails.
    return std::nullopt;
  }
  // x_k = (h.b - sum_{j != k} h.a[j] x_j) / pivot = base + sum_j coef[j] y_j
  const double base = h.b / pivot;
  LpVector coef{};  // indexed in the reduced variables
  auto reduced = [&](int j) { return j < k ? j : j - 1; };
  for (int j = 0; j < dim; ++j)
    if (j != k) coef[reduced(j)] = -h.a[j] / pivot;
  const int sub = dim - 1;

  std::vector<LpConstraint>& rows = scratch(level);
  rows.clear();
  auto addRow = [&](const LpVector& a, double b) -> bool {
    LpConstraint r;
    for (int j = 0; j < dim; ++j)
      if (j != k) r.a[reduced(j)] = a[j] + a[k] * coef[reduced(j)];
    r.b = b - a[k] * base;
    double norm = 0;
    for (int j = 0; j < sub; ++j) norm += r.a[j] * r.a[j];
    norm = std::sqrt(norm);
    // Rows are unit length on entry; a projected row this short is parallel to the hyperplane:
    // it holds everywhere on it or nowhere.
    if (norm < 1e-12) return r.b >= -kLpRelativeFeasibility * (1.0 + std::abs(base));
    for (int j = 0; j < sub; ++j) r.a[j] /= norm;
    r.b /= norm;
    rows.push_back(r);
    return true;
  };
  for (size_t r = 0; r < i; ++r)
    if (!addRow(constraints[r].a, constraints[r].b)) return std::nullopt;
  {
    LpVector e{};
    e[k] = 1;
    if (!addRow(e, hi[k])) return std::nullopt;
    e[k] = -1;
    if (!addRow(e, -lo[k])) return std::nullopt;
  }
  // Seidel's expected-time bound needs a random order; a deterministic shuffle gives it.
  for (size_t r = rows.size(); r > 1; --r) std::swap(rows[r - 1], rows[splitmix(rng_) % r]);

  LpVector subC{}, subLo{}, subHi{};
  for (int j = 0; j < dim; ++j) {
    if (j == k) continue;
    subC[reduced(j)] = c[j] + c[k] * coef[reduced(j)];
    subLo[reduced(j)] = lo[j];
    subHi[reduced(j)] = hi[j];
  }
  // The recursion only touches deeper scratch levels, which exist already (see scratch()).
  std::optional<LpVector> y =
      run(sub, std::span<const LpConstraint>(rows), 0, boxOptimum(sub, subC, subLo, subHi), subC,
          subLo, subHi, level + 1);
  if (!y) return std::nullopt;
  LpVector x{};
  double xk = base;
  for (int j = 0; j < dim; ++j) {
    if (j == k) continue;
    x[j] = (*y)[reduced(j)];
    xk += coef[reduced(j)] * x[j];
  }
  x[k] = xk;
  return x;
}

}  // namespace gv
