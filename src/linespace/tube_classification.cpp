// Multi-blocker logic and statistics of incremental blocker maintenance. Paper §6.2, §7.4.
#include "linespace/tube_classification.h"

#include <cmath>

#include "geometry/coplanar_cover.h"

namespace gv {

void OutcomeCounts::add(const BlockerVerdict& v) {
  switch (v.outcome) {
    case BlockerOutcome::Occludes:
      ++occludes;
      break;
    case BlockerOutcome::Impinges:
      ++impinges;
      break;
    case BlockerOutcome::Disjoint:
      ++disjoint;
      break;
    case BlockerOutcome::Punt:
      ++punt;
      break;
  }
  byPlanes += v.byPlanes;
  straddling += !v.between && !v.byPlanes;
  puntsTested += v.wasPunt;
  puntsRemoved += v.wasPunt && v.outcome == BlockerOutcome::Disjoint;
}

OutcomeCounts& OutcomeCounts::operator+=(const OutcomeCounts& o) {
  occludes += o.occludes;
  impinges += o.impinges;
  disjoint += o.disjoint;
  punt += o.punt;
  byPlanes += o.byPlanes;
  straddling += o.straddling;
  puntsTested += o.puntsTested;
  puntsRemoved += o.puntsRemoved;
  coplanarCovers += o.coplanarCovers;
  return *this;
}

TubeVerdict classifyTube(const Tube& tube, std::span<const uint32_t> blockers,
                         const BlockerTable& table, const Tolerance& tol,
                         const TubeOptions& options) {
  TubeVerdict t;
  std::vector<uint32_t> between;  // kept blockers with S and R on opposite sides of their plane
  for (const uint32_t id : blockers) {
    const BlockerVerdict v = classifyBlocker(tube, table[id], tol, options);
    t.counts.add(v);
    if (v.outcome == BlockerOutcome::Occludes) {
      t.status = VisibilityStatus::Invisible;
      t.proof = id;
      t.blockers.clear();
      return t;
    }
    if (v.outcome == BlockerOutcome::Disjoint) continue;
    t.blockers.push_back(id);
    if (v.between) between.push_back(id);
  }
  t.status = t.blockers.empty() ? VisibilityStatus::Visible : VisibilityStatus::Partial;
  if (!options.coplanarCover || between.size() < 2) return t;
  // Coplanar groups of the between blockers, each tested as one wall.
  std::vector<PlanarOutline> outlines;
  outlines.reserve(between.size());
  for (const uint32_t id : between) outlines.push_back({&table[id].plane, table[id].vertices});
  CoplanarGroups groups;
  if (someCoplanarGroupCovers(tube.source(), tube.receiver(), outlines, tol.length(), groups)) {
    t.status = VisibilityStatus::Invisible;
    t.proof = between[groups.members.front()];
    t.blockers.clear();
    ++t.counts.coplanarCovers;
  }
  return t;
}

LevelStats LinespaceStats::total() const {
  LevelStats sum;
  for (const LevelStats& l : levels) {
    sum.tubes += l.tubes;
    sum.visible += l.visible;
    sum.partial += l.partial;
    sum.invisible += l.invisible;
    sum.inheritedVisible += l.inheritedVisible;
    sum.blockers += l.blockers;
  }
  return sum;
}

}  // namespace gv
