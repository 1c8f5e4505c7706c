// Cluster links: candidate lookup, the transfer bound, and the sampled taps.
#include "radiosity/cluster_links.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "radiosity/link_sampling.h"
#include "radiosity/polygon_sampling.h"

namespace gv {

CandidatePairs::CandidatePairs(LinkVisibility& visibility, const ClusterTree& clusters)
    : clusters_(&clusters) {
  const size_t n = clusters.order().size();
  if (visibility.everyPairIsCandidate()) {
    every_ = true;
    count_ = n < 2 ? 0 : n * (n - 1) / 2;
    return;
  }
  if (const PatchCellReach* cells = visibility.candidateCells()) {
    cells_ = cells;
    count_ = cells->countPairs();
    indexCells(clusters);
    return;
  }
  position_.assign(n, 0);
  for (size_t i = 0; i < n; ++i) position_[clusters.order()[i]] = static_cast<uint32_t>(i);
  struct Pair {
    uint32_t a, b;
    TubeId tube;
  };
  std::vector<Pair> pairs;
  visibility.forEachCandidatePair([&](uint32_t a, uint32_t b, TubeId tube) {
    pairs.push_back({position_[a], position_[b], tube});
  });
  count_ = pairs.size();
  rowBegin_.assign(n + 1, 0);
  for (const Pair& p : pairs) {
    ++rowBegin_[p.a + 1];
    ++rowBegin_[p.b + 1];
  }
  for (size_t i = 0; i < n; ++i) rowBegin_[i + 1] += rowBegin_[i];
  entries_.resize(rowBegin_[n]);
  std::vector<size_t> next(rowBegin_.begin(), rowBegin_.end() - 1);
  for (const Pair& p : pairs) {
    entries_[next[p.a]++] = uint64_t{p.b} << 32 | p.tube;
    entries_[next[p.b]++] = uint64_t{p.a} << 32 | p.tube;
  }
  pairs = {};
  for (size_t i = 0; i < n; ++i)
    std::sort(entries_.begin() + static_cast<long>(rowBegin_[i]),
              entries_.begin() + static_cast<long>(rowBegin_[i + 1]));
}

/// Clusters with more cells than this keep the union of their cells' reach as a set: a test
/// against them is then one bit per cell of the other cluster.
constexpr size_t kListedCells = 8;

void CandidatePairs::indexCells(const ClusterTree& clusters) {
  const size_t nodes = clusters.size();
  std::vector<std::vector<uint32_t>> cellsOf(nodes);
  clusterUnplaced_.assign(nodes, 0);
  // Children have larger ids than their parent: bottom-up is descending ids.
  for (size_t i = nodes; i-- > 0;) {
    const Cluster& c = clusters[static_cast<uint32_t>(i)];
    if (c.isLeaf()) {
      const uint32_t p = clusters.patchesOf(static_cast<uint32_t>(i))[0];
      cellsOf[i] = cells_->cellsOf(p);
      clusterUnplaced_[i] = cellsOf[i].empty();
      continue;
    }
    const std::vector<uint32_t>& l = cellsOf[c.left];
    const std::vector<uint32_t>& r = cellsOf[c.right];
    std::set_union(l.begin(), l.end(), r.begin(), r.end(), std::back_inserter(cellsOf[i]));
    clusterUnplaced_[i] = clusterUnplaced_[c.left] | clusterUnplaced_[c.right];
  }
  clusterCellBegin_.assign(nodes + 1, 0);
  for (size_t i = 0; i < nodes; ++i)
    clusterCellBegin_[i + 1] = clusterCellBegin_[i] + cellsOf[i].size();
  clusterCells_.reserve(clusterCellBegin_[nodes]);
  clusterReachIndex_.assign(nodes, UINT32_MAX);
  for (size_t i = 0; i < nodes; ++i) {
    clusterCells_.insert(clusterCells_.end(), cellsOf[i].begin(), cellsOf[i].end());
    if (cellsOf[i].size() <= kListedCells) continue;
    clusterReachIndex_[i] = static_cast<uint32_t>(clusterReach_.size());
    CellSet& reach = clusterReach_.emplace_back(cells_->cellCount());
    for (uint32_t c : cellsOf[i]) reach.unite(cells_->reach(c));
  }
}

bool CandidatePairs::cellsMaySee(uint32_t x, uint32_t y) const {
  if (clusterUnplaced_[x] || clusterUnplaced_[y]) return true;
  auto cellsOf = [&](uint32_t i) {
    return std::span(clusterCells_)
        .subspan(clusterCellBegin_[i], clusterCellBegin_[i + 1] - clusterCellBegin_[i]);
  };
  // x: the cluster with fewer cells. Reach is symmetric: a cell of x sees a cell of y exactly
  // when it lies in the union of the reach of y's cells.
  if (cellsOf(x).size() > cellsOf(y).size()) std::swap(x, y);
  if (clusterReachIndex_[y] != UINT32_MAX) {
    const CellSet& reachY = clusterReach_[clusterReachIndex_[y]];
    for (uint32_t c : cellsOf(x))
      if (reachY.contains(c)) return true;
    return false;
  }
  for (uint32_t c : cellsOf(x))
    for (uint32_t d : cellsOf(y))
      if (cells_->reach(c).contains(d)) return true;
  return false;
}

std::optional<TubeId> CandidatePairs::find(uint32_t a, uint32_t b) const {
  if (every_) return kNoTube;
  if (cells_) {
    if (cells_->maySee(a, b)) return kNoTube;
    return std::nullopt;
  }
  const uint32_t pa = position_[a], pb = position_[b];
  const std::span<const uint64_t> r = row(pa);
  const auto it = std::lower_bound(r.begin(), r.end(), uint64_t{pb} << 32);
  if (it == r.end() || (*it >> 32) != pb) return std::nullopt;
  return static_cast<TubeId>(*it & 0xffffffffu);
}

bool CandidatePairs::anyBetween(uint32_t xId, uint32_t yId) const {
  if (every_) return true;
  if (cells_) return cellsMaySee(xId, yId);
  const Cluster& x = (*clusters_)[xId];
  const Cluster& y = (*clusters_)[yId];
  const Cluster& small = x.size() <= y.size() ? x : y;
  const Cluster& large = x.size() <= y.size() ? y : x;
  for (uint32_t i = small.begin; i < small.end; ++i) {
    const std::span<const uint64_t> r = row(i);
    const auto it = std::lower_bound(r.begin(), r.end(), uint64_t{large.begin} << 32);
    if (it != r.end() && (*it >> 32) < large.end) return true;
  }
  return false;
}

ClusterTransfer clusterTransfer(const Cluster& x, const Cluster& y, double brightX,
                                double brightY) {
  const double d = boxDistance(x.box, y.box);
  if (!(d > 0)) return {INFINITY, INFINITY};
  const double piD2 = std::numbers::pi * d * d;
  // Only well-separated clusters: a sample carries up to A_Y / (π d²) / samplesPerPatch, and
  // close clusters (whose light may still be 0 in the first round) would hand single samples
  // form factors near or over 1, noise enough to make the solve diverge.
  if (std::max(x.area, y.area) > kMaxClusterFormFactor * piD2) return {INFINITY, INFINITY};
  return {x.reflectance * x.area * brightY * y.area / piD2,
          y.reflectance * y.area * brightX * x.area / piD2};
}

double clusterTransferBound(const Cluster& x, const Cluster& y, double brightX, double brightY) {
  const ClusterTransfer t = clusterTransfer(x, y, brightX, brightY);
  return std::max(t.intoX, t.intoY);
}

SourcePicker::SourcePicker(const ClusterTree& clusters, std::span<const double> brightness)
    : clusters_(clusters) {
  const std::span<const double> areaBefore = clusters.areaBefore();
  const std::span<const uint32_t> order = clusters.order();
  powerBefore_.assign(order.size() + 1, 0.0);
  for (size_t i = 0; i < order.size(); ++i)
    powerBefore_[i + 1] =
        powerBefore_[i] + (areaBefore[i + 1] - areaBefore[i]) * brightness[order[i]];
}

SourcePicker::Pick SourcePicker::pick(uint32_t cluster, double u) const {
  const Cluster& c = clusters_[cluster];
  const std::span<const double> areaBefore = clusters_.areaBefore();
  const double power = powerBefore_[c.end] - powerBefore_[c.begin];
  uint32_t at = 0;
  if (!(power > 0)) {
    at = positionByWeight(areaBefore, c.begin, c.end, u);
  } else if (u < 0.5) {
    at = positionByWeight(areaBefore, c.begin, c.end, 2 * u);
  } else {
    at = positionByWeight(powerBefore_, c.begin, c.end, 2 * u - 1);
  }
  const double area = areaBefore[at + 1] - areaBefore[at];
  // P(q) = ½ A_q / A_X + ½ A_q b_q / P_X (or A_q / A_X without power); weight = A_q / P(q).
  double weight = c.area;
  if (power > 0) {
    const double brightness = area > 0 ? (powerBefore_[at + 1] - powerBefore_[at]) / area : 0;
    weight = 1 / (0.5 / c.area + 0.5 * brightness / power);
  }
  return {clusters_.order()[at], weight};
}

namespace {

/// Whether any corner of `box` lies strictly in front of `plane`.
bool inFront(const Plane& plane, const Aabb& box) {
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner{c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y,
                      c & 4 ? box.hi.z : box.lo.z};
    if (plane.distance(corner) > 0) return true;
  }
  return false;
}

/// The taps into the patches of `to` from cluster `from` (one direction of a link).
void sampleInto(const ClusterTree& clusters, const SourcePicker& sources,
                const ElementTree& elements, const CandidatePairs& candidates,
                const LinkVisibility& visibility, const Tolerance& tol, uint32_t to, uint32_t from,
                int samplesPerPatch, SplitMix64& rng, ClusterSampling& out) {
  const Aabb& sourceBox = clusters[from].box;
  for (const uint32_t p : clusters.patchesOf(to)) {
    const ConvexPolygon& receiver = elements[p].polygon;
    // The source cluster's box wholly behind the receiver's plane: nothing to gather.
    if (!inFront(receiver.plane, sourceBox)) continue;
    const std::vector<Vec3> points = stratifiedPoints(receiver.vertices, samplesPerPatch, rng);
    for (const Vec3& x : points) {
      const SourcePicker::Pick picked = sources.pick(from, rng.uniform());
      const uint32_t q = picked.patch;
      const ConvexPolygon& source = elements[q].polygon;
      // Behind the source's plane: no point of it faces x (most picks in a large cluster).
      if (!(source.plane.distance(x) > 0)) continue;
      const Vec3 y = uniformPoint(source.vertices, rng);
      // cos θx cos θy / r², 0 when either faces away: no ray needed.
      const double kernel = kernelWeight(x, receiver.normal(), y, source.normal());
      if (!(kernel > 0)) continue;
      const std::optional<TubeId> tube = candidates.find(p, q);
      if (!tube) continue;
      ++out.rays;
      auto blocked = [&](const Vec3& start, const Vec3& end) {
        return visibility.segmentBlocked(p, start, q, end, *tube);
      };
      if (blocked(x, y)) continue;
      // A single clear sample carries the whole tap: one through a crack is a leak.
      out.rays += 2;
      if (throughCrack(x, y, tol, blocked)) continue;
      out.taps.push_back(
          {p, elements.deepestContaining(q, y),
           static_cast<float>(picked.weight / samplesPerPatch * kernel / std::numbers::pi),
           StoredPoint(y)});
    }
  }
}

}  // namespace

ClusterSampling sampleClusterLink(const ClusterTree& clusters, const SourcePicker& sources,
                                  const ElementTree& elements, const CandidatePairs& candidates,
                                  const LinkVisibility& visibility, const Tolerance& tol,
                                  uint32_t x, uint32_t y, int samplesPerPatch, uint64_t seed) {
  ClusterSampling out;
  SplitMix64 rng(seed);
  sampleInto(clusters, sources, elements, candidates, visibility, tol, x, y, samplesPerPatch, rng,
             out);
  sampleInto(clusters, sources, elements, candidates, visibility, tol, y, x, samplesPerPatch, rng,
             out);
  return out;
}

}  // namespace gv
