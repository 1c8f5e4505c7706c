// "Might see" sets: for each portal and direction of travel, a superset of the cells a sightline
// can reach after crossing it (the idea of Quake `vis`'s base pass, paper §4.1's pruning in
// spirit). The searches stop as soon as nothing new can be reached — they enumerate portal
// sequences, whose number explodes in open space, so this pruning is what makes them fast.
#pragma once

#include <cstdint>
#include <vector>

#include "bsp/subdivision.h"
#include "visibility/cell_set.h"

namespace gv {

/// For portal p crossed into p.front (`intoFront`) or into p.back: the cells a line crossing it
/// that way may reach next. A cell is included when a chain of portals leads to it on which every
/// portal Q passes two necessary tests for a line that crossed P earlier: some vertex of Q is not
/// behind P's plane (the line moves away from P's plane after crossing it) and some vertex of P is
/// not in front of Q's plane (P lies before Q along the line). Any real continuation passes both,
/// so the set is a superset (with a tolerance, never tighter than exact).
class MightSee {
 public:
  /// Computes the sets; above `maxCells` cells (memory is portals × cells bits) it stores nothing
  /// and every query answers "all cells".
  MightSee(const Subdivision& sub, const Tolerance& tol, size_t maxCells = 40000);
  const CellSet& through(uint32_t portal, bool intoFront) const {
    return sets_.empty() ? all_ : sets_[2 * portal + (intoFront ? 1 : 0)];
  }
  bool enabled() const { return !sets_.empty(); }

 private:
  std::vector<CellSet> sets_;
  CellSet all_;
};

}  // namespace gv
