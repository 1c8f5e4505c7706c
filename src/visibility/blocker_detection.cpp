// Blocker detection (paper §5): interactions and their blocker lists from the patch searches'
// seen lists, built in parallel and handed on in order (see blocker_detection.h).
#include "visibility/blocker_detection.h"

#include <tbb/concurrent_queue.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <utility>

#include "geometry/coplanar_cover.h"
#include "util/timing.h"
#include "visibility/blocker_lists.h"
#include "visibility/hull_overlap.h"
#include "visibility/patch_grid.h"
#include "visibility/search_deadline.h"
#include "visibility/single_occluder.h"

namespace gv {
namespace {

/// Blocker lists are built for this many entries of the sources' seen lists at a time (one
/// pipeline token; a source's pairs come from its entries): small enough that the chunks in
/// flight are little memory (at most this many pairs each), large enough to amortise the
/// hand-over.
constexpr uint64_t kSeenPerChunk = 1024;
/// Chunks in flight per thread: room for threads to work ahead of a slow chunk that holds up
/// the in-order hand-over.
constexpr size_t kChunksInFlightPerThread = 3;
/// Flags of the blocker stage's candidates: seen from the pair's S, from its T.
constexpr uint8_t kFromS = 1, kFromT = 2;
/// A membership flag costs about this fraction of a binary search in seen(T) (both per
/// candidate; flags need a pass over seen(T) to set and one to clear).
constexpr size_t kFlagsPerSearch = 4;

/// Up to this many patches, every seen list is also kept as two rows of bits (2 n² bits: 64 MiB
/// at the limit), so that "seen from R" is one bit per candidate instead of a pass over seen(R)
/// per pair to set flags and one to clear them, and "R saw S's front" one bit per pair instead
/// of a binary search in seen(R) (a cache miss per level on lists of thousands).
constexpr size_t kMaxSeenBitsPatches = 16384;

/// Pairs of one source are taken in groups of up to this many receivers (consecutive in the
/// seen list, so in id order, where faces cut into patches and the faces of one brush lie
/// together) whose boxes fit in a box at most kGroupSpread times as large as its distance from
/// the source: the candidates of the group's shaft, conv(S ∪ box), are gathered from the grid
/// once, and each pair picks its own from those instead of from the grid.
/// (retrojam1's blocker stage, 2 threads: 7.3 s ungrouped, 5.7 s at 16 and 0.25, 5.5 s at 32
/// and 0.5 or at 64 and 0.5; 5-8 % less on doom-fd2-map03 and E1M1, nothing on q3-oa_ctf2.)
constexpr size_t kMaxGroup = 32;
constexpr double kGroupSpread = 0.5;

/// Blockers that hid a source's last pairs tried first on its next (BlockerDetection::
/// hiddenByRecent); no pair's blockers are gathered when one of these hides it.
constexpr size_t kRecentHiders = 4;
/// addBlockers' answer for a pair no blocker hides whole.
constexpr uint32_t kNoHider = UINT32_MAX;
/// addBlockers' answer for a pair that blockers in one plane hide together (a wall of pieces).
constexpr uint32_t kWallHider = UINT32_MAX - 1;

/// A chunk whose id array grew past this (16 MiB) gives it back after the hand-over instead of
/// keeping it for reuse.
constexpr size_t kKeptIdsPerChunk = size_t{1} << 22;

/// Sorts distinct ids in [0, 64 bits.size()): by std::sort when there are few, else by setting
/// their bits in `bits` (all clear on entry and on return) and reading them back in order, which
/// is cheaper once the ids are more than a sparse sample of the range.
void sortIds(std::span<uint32_t> ids, std::vector<uint64_t>& bits) {
  if (ids.size() < 64 || double(ids.size()) * std::log2(double(ids.size())) < double(bits.size())) {
    std::sort(ids.begin(), ids.end());
    return;
  }
  uint32_t lo = UINT32_MAX, hi = 0;
  for (uint32_t id : ids) {
    bits[id >> 6] |= uint64_t{1} << (id & 63);
    lo = std::min(lo, id);
    hi = std::max(hi, id);
  }
  size_t k = 0;
  for (size_t word = lo >> 6; word <= (hi >> 6); ++word) {
    for (uint64_t b = bits[word]; b; b &= b - 1)
      ids[k++] = static_cast<uint32_t>(word * 64 + size_t(std::countr_zero(b)));
    bits[word] = 0;
  }
}

/// One thread's scratch memory of the blocker stage.
struct BlockerWorker {
  std::vector<uint8_t> seen;       ///< per patch: kFromS (in seen(S)) | kFromT (in seen(T))
  std::vector<uint32_t> gathered;  ///< room for every patch: one pair's candidates
  std::vector<uint32_t> group;     ///< room for every patch: a group's shaft's candidates
  std::vector<uint64_t> bits;      ///< one per patch, all clear between calls of sortIds
  std::vector<uint8_t> kinds;      ///< per entry of the current range of a seen list: EntryKind
  /// Per patch c: sideOfSlab(c, S) for the source S = sideSource[c] − 1 (0: not known yet). A
  /// source's pairs meet the same blockers again and again; S's side of each is found once.
  std::vector<uint32_t> sideSource;
  std::vector<int8_t> sideOfSource;
  std::vector<uint32_t> hiders;  ///< the blockers that hid the source's last pairs, latest first
  /// The current pair's blockers with S and T strictly on opposite sides of their plane (ids,
  /// and their outlines), and scratch for the coplanar groups among them (hiddenByWall).
  std::vector<uint32_t> between;
  std::vector<PlanarOutline> betweenOutlines;
  CoplanarGroups groups;
  /// The blockers that hid the source's last pair hidden by a wall (hiddenByWall), tried on its
  /// next pairs as `hiders` are, and room for their outlines.
  std::vector<uint32_t> recentWall;
  std::vector<PlanarOutline> wall;
};

/// What an entry (s, t) of seen(s) gives.
enum EntryKind : uint8_t {
  kNoPair,    ///< t <= s, or not seen front to front both ways, or the two cannot face
  kSameCell,  ///< a pair the patch search found VISIBLE inside one convex cell
  kTested,    ///< a pair whose blockers are looked for
};

/// A pipeline token: entries [begin, end) of the seen lists and the pairs they gave.
struct Chunk {
  uint64_t begin = 0, end = 0;  ///< positions [begin, end) of the seen lists
  size_t sourcesDone = 0;       ///< sources whose lists end by `end`
  BlockerLists lists;
  uint64_t visible = 0, partial = 0, sameCell = 0;
  uint64_t hidden = 0;        ///< pairs dropped: hidden whole behind one of their blockers
  uint64_t hiddenByWall = 0;  ///< pairs dropped: hidden by coplanar blockers together
};

/// The seen lists and the patches laid out for the blocker tests.
class BlockerDetection {
 public:
  BlockerDetection(const Scene& scene, const std::vector<PatchSearchResult>& seen,
                   const Tolerance& tol)
      : scene_(scene), seen_(seen), tol_(tol), n_(scene.patches.size()), patchBoxes_(n_) {
    const size_t n = n_;
    for (size_t p = 0; p < n; ++p) patchBoxes_[p] = scene.patches[p].polygon.bounds();
    // Candidates come from a grid of patch boxes: only patches whose boxes meet conv(S, T)'s box
    // can meet conv(S, T), so the scan no longer walks all of seen(S) and seen(T) for every pair.
    grid_.emplace(patchBoxes_);
    // The candidates' vertices in one array, patch by patch: candidates are tested in id order,
    // so the test walks this array forwards instead of chasing a vector per patch.
    vertexStart_.assign(n + 1, 0);
    for (size_t p = 0; p < n; ++p)
      vertexStart_[p + 1] = vertexStart_[p] + uint32_t(scene.patches[p].polygon.vertices.size());
    vertices_.resize(vertexStart_[n]);
    for (size_t p = 0; p < n; ++p)
      std::copy(scene.patches[p].polygon.vertices.begin(), scene.patches[p].polygon.vertices.end(),
                vertices_.begin() + vertexStart_[p]);
    // The candidates' plane normals in one array (a Patch is far larger than its normal).
    normals_.resize(n);
    normalLengths_.resize(n);
    slabs_.resize(n);
    for (size_t p = 0; p < n; ++p) slabs_[p] = occluderSlab(scene.patches[p].polygon);
    // Their edges as inward half-planes, beside the vertices: crossesInside runs for every
    // blocker between a pair's ends and most fail at the first crossing point, so preparing the
    // edges on each call was most of its cost.
    edges_.resize(vertexStart_[n]);
    edgesUsable_.resize(n);
    for (size_t p = 0; p < n; ++p)
      edgesUsable_[p] = inwardEdges(scene.patches[p].polygon,
                                    std::span<InwardEdge>(edges_.data() + vertexStart_[p],
                                                          edges_.data() + vertexStart_[p + 1]));
    for (size_t p = 0; p < n; ++p) {
      normals_[p] = scene.patches[p].polygon.plane.normal;
      normalLengths_[p] = length(normals_[p]);
    }
    // Work is counted in entries of the seen lists, all sources' lists one after another: source
    // s holds positions [seenStart[s], seenStart[s + 1]), and its pairs (s, t) come from them.
    seenStart_.assign(n + 1, 0);
    for (size_t p = 0; p < n; ++p) seenStart_[p + 1] = seenStart_[p] + seen[p].seen.size();
    if (n <= kMaxSeenBitsPatches) {
      seenWords_ = (n + 63) / 64;
      seenBits_.assign(n * seenWords_, 0);
      frontBits_.assign(n * seenWords_, 0);
      for (size_t p = 0; p < n; ++p)
        for (uint32_t e : seen[p].seen) {
          const uint32_t c = seenPatch(e);
          const uint64_t bit = uint64_t{1} << (c & 63);
          seenBits_[p * seenWords_ + (c >> 6)] |= bit;
          if (seenFlags(e) & kSeenFront) frontBits_[p * seenWords_ + (c >> 6)] |= bit;
        }
    }
  }

  size_t patchCount() const { return n_; }
  const std::vector<Aabb>& patchBoxes() const { return patchBoxes_; }
  /// Per source, where its entries start among all sources' (and the total, last).
  const std::vector<uint64_t>& seenStart() const { return seenStart_; }

  BlockerWorker makeWorker() const {
    return BlockerWorker{std::vector<uint8_t>(n_, 0),
                         std::vector<uint32_t>(grid_->patchCount()),
                         std::vector<uint32_t>(grid_->patchCount()),
                         std::vector<uint64_t>((n_ + 63) / 64, 0),
                         {},
                         std::vector<uint32_t>(n_, 0),
                         std::vector<int8_t>(n_, 0),
                         {},
                         {},
                         {},
                         {},
                         {},
                         {}};
  }

  /// The pairs of the chunk's entries, with their blocker lists.
  void fill(BlockerWorker& w, Chunk& chunk) const {
    const size_t n = n_;
    const std::vector<uint64_t>& seenStart = seenStart_;
    // The first source with entries at or after `begin`, then on while its entries start before
    // `end`.
    size_t s = size_t(std::upper_bound(seenStart.begin(), seenStart.end(), chunk.begin) -
                      seenStart.begin()) -
               1;
    for (; s < n && seenStart[s] < chunk.end; ++s) {
      const uint64_t from = std::max(chunk.begin, seenStart[s]);
      const uint64_t to = std::min(chunk.end, seenStart[s + 1]);
      if (from < to)
        blockersOf(w, static_cast<uint32_t>(s), size_t(from - seenStart[s]),
                   size_t(to - seenStart[s]), chunk);
    }
  }

 private:
  uint8_t flagsOf(uint32_t s, uint32_t t) const {
    const auto& v = seen_[s].seen;
    auto it = std::lower_bound(v.begin(), v.end(), seenEntry(t, 0));
    return (it != v.end() && seenPatch(*it) == t) ? seenFlags(*it) : 0;
  }
  /// Whether t's search saw the front of s.
  bool seesFront(uint32_t t, uint32_t s) const {
    if (!frontBits_.empty()) return (frontBits_[size_t(t) * seenWords_ + (s >> 6)] >> (s & 63)) & 1;
    return flagsOf(t, s) & kSeenFront;
  }
  bool isSameCellVisible(uint32_t s, uint32_t t) const {
    const auto& v = seen_[s].sameCellVisible;
    return std::binary_search(v.begin(), v.end(), t);
  }

  /// What entry `e` of seen(s) gives.
  EntryKind kindOf(uint32_t s, uint32_t e) const {
    const uint32_t t = seenPatch(e);
    if (t <= s) return kNoPair;
    // Both searches are conservative and a sightline runs both ways, so a real pair is seen
    // front to front from each end: requiring both is exact pruning, not a guess.
    const bool front = (seenFlags(e) & kSeenFront) && seesFront(t, s);
    if (!front || !canFace(scene_.patches[s].polygon, scene_.patches[t].polygon, tol_.length()))
      return kNoPair;
    return (isSameCellVisible(s, t) || isSameCellVisible(t, s)) ? kSameCell : kTested;
  }

  /// Whether receivers filling box `g` may share one shaft from the source's box `sBox`.
  static bool fitsGroup(const Aabb& sBox, const Aabb& g) {
    const Vec3 e = g.extent();
    const double spread = std::max({e.x, e.y, e.z});
    return spread <= kGroupSpread * length(g.center() - sBox.center());
  }

  /// The interactions (s, t), t > s, for entries [from, to) of seen(s), in t order, with their
  /// blocker lists, appended to `chunk`.
  void blockersOf(BlockerWorker& w, uint32_t s, size_t from, size_t to, Chunk& chunk) const {
    const ConvexPolygon& sp = scene_.patches[s].polygon;
    const std::vector<uint32_t>& entries = seen_[s].seen;
    for (uint32_t e : entries) w.seen[seenPatch(e)] = kFromS;
    w.kinds.resize(to - from);
    for (size_t k = from; k < to; ++k) w.kinds[k - from] = kindOf(s, entries[k]);
    w.hiders.clear();
    w.recentWall.clear();
    for (size_t k = from; k < to;) {
      // The run [k, end) whose tested pairs make one group.
      Aabb groupBox;
      size_t members = 0, end = k;
      for (; end < to; ++end) {
        if (w.kinds[end - from] != kTested) continue;
        Aabb grown = groupBox;
        grown.add(patchBoxes_[seenPatch(entries[end])]);
        if (members > 0 && (members == kMaxGroup || !fitsGroup(patchBoxes_[s], grown))) break;
        groupBox = grown;
        ++members;
      }
      std::optional<std::span<const uint32_t>> group;  // gathered for the first pair that asks
      for (; k < end; ++k) {
        const EntryKind kind = static_cast<EntryKind>(w.kinds[k - from]);
        if (kind == kNoPair) continue;
        const uint32_t t = seenPatch(entries[k]);
        if (kind == kTested && hiddenByRecent(w, s, t)) {
          ++chunk.hidden;
          continue;
        }
        if (kind == kTested && hiddenByRecentWall(w, s, t)) {
          ++chunk.hiddenByWall;
          continue;
        }
        if (kind == kTested && members >= 2 && !group) {
          const PairHull shaft(sp, groupBox, tol_);
          Aabb box = groupBox;
          box.add(patchBoxes_[s]);
          group.emplace(w.group.data(),
                        grid_->gatherInto(box, tol_.length(), w.group.data(), &shaft));
          // Sorted once here, each pair's candidates, picked from it in order, come out sorted.
          sortIds(std::span<uint32_t>(w.group.data(), group->size()), w.bits);
        }
        BlockerLists& lists = chunk.lists;
        lists.addPair(s, t);  // its blockers are appended below, straight into the chunk
        if (kind == kSameCell) {
          ++chunk.sameCell;
        } else if (const uint32_t hider = addBlockers(w, s, t, group, lists); hider != kNoHider) {
          lists.popPair();
          if (hider == kWallHider) {
            ++chunk.hiddenByWall;
          } else {
            ++chunk.hidden;
            rememberHider(w, hider);
          }
          continue;
        }
        ++(lists.blockers(lists.size() - 1).empty() ? chunk.visible : chunk.partial);
      }
    }
    for (uint32_t e : entries) w.seen[seenPatch(e)] = 0;
  }

  /// Whether one of the blockers that hid the source's last pairs hides (s, t) whole too: the
  /// next receivers are mostly neighbours of the last, behind the same wall. Exact (hidesWhole),
  /// so the pair is INVISIBLE whether or not the wall is one of its own candidates; a hit moves
  /// the blocker to the front.
  bool hiddenByRecent(BlockerWorker& w, uint32_t s, uint32_t t) const {
    const double margin = 2 * tol_.planeOffset();
    for (size_t i = 0; i < w.hiders.size(); ++i)
      if (hides(w, w.hiders[i], s, t, margin)) {
        std::rotate(w.hiders.begin(), w.hiders.begin() + i, w.hiders.begin() + i + 1);
        return true;
      }
    return false;
  }
  static void rememberHider(BlockerWorker& w, uint32_t c) {
    if (w.hiders.size() == kRecentHiders) w.hiders.pop_back();
    w.hiders.insert(w.hiders.begin(), c);
  }

  /// hidesWhole(c, S, T, margin), with c's slab prepared and S's side of it kept per source.
  bool hides(BlockerWorker& w, uint32_t c, uint32_t s, uint32_t t, double margin) const {
    return between(w, c, s, t, margin) &&
           crossesInside(c, scene_.patches[s].polygon, scene_.patches[t].polygon, margin);
  }
  /// crossesInside(c, slab, S, T, margin) with c's edges prepared.
  bool crossesInside(uint32_t c, const ConvexPolygon& sp, const ConvexPolygon& tp,
                     double margin) const {
    return edgesUsable_[c] &&
           gv::crossesInside(scene_.patches[c].polygon, slabs_[c],
                             std::span<const InwardEdge>(edges_.data() + vertexStart_[c],
                                                         edges_.data() + vertexStart_[c + 1]),
                             sp, tp, margin);
  }
  /// Whether S and T lie on opposite sides of c's slab, every vertex beyond it by more than
  /// `margin` (S's side kept per source).
  bool between(BlockerWorker& w, uint32_t c, uint32_t s, uint32_t t, double margin) const {
    const ConvexPolygon& blocker = scene_.patches[c].polygon;
    if (w.sideSource[c] != s + 1) {
      w.sideSource[c] = s + 1;
      w.sideOfSource[c] =
          static_cast<int8_t>(sideOfSlab(blocker, slabs_[c], scene_.patches[s].polygon, margin));
    }
    const int ss = w.sideOfSource[c];
    return ss != 0 && sideOfSlab(blocker, slabs_[c], scene_.patches[t].polygon, margin) == -ss;
  }

  /// Whether blockers of w.between lying in one plane hide T from S together
  /// (someCoplanarGroupCovers): a wall cut into pieces, by brush faces or by the BSP, that no
  /// single piece covers. Every one lies between S and T beyond the contact margin, so no
  /// segment the contract's contact rule lets through is lost. Exact up to the tolerance, as
  /// hidesWhole is: the pair is INVISIBLE. (retrojam1: 852,896 pairs listed without this test,
  /// 742,871 with it; excess 51.0 -> 44.7 %.) The wall found becomes w.recentWall.
  bool hiddenByWall(BlockerWorker& w, uint32_t s, uint32_t t) const {
    if (!someCoplanarGroupCovers(scene_.patches[s].polygon, scene_.patches[t].polygon,
                                 w.betweenOutlines, tol_.length(), w.groups))
      return false;
    w.recentWall.clear();
    for (uint32_t k : w.groups.members) w.recentWall.push_back(w.between[k]);
    return true;
  }

  /// Whether the wall that hid the source's last pair hidden by a wall hides (s, t) too: the
  /// next receivers are mostly neighbours of the last, behind the same wall. The same test as
  /// hiddenByWall's (each piece between S and T beyond the margin, then the cover), on pieces
  /// that need not be (s, t)'s blockers: a cover by any patches proves the pair INVISIBLE.
  bool hiddenByRecentWall(BlockerWorker& w, uint32_t s, uint32_t t) const {
    if (w.recentWall.empty()) return false;
    const double margin = 2 * tol_.planeOffset();
    w.wall.clear();
    for (uint32_t c : w.recentWall) {
      if (!between(w, c, s, t, margin)) return false;
      const ConvexPolygon& b = scene_.patches[c].polygon;
      w.wall.push_back(PlanarOutline{&b.plane, b.vertices});
    }
    return coplanarOutlinesCover(scene_.patches[s].polygon, scene_.patches[t].polygon, w.wall,
                                 tol_.length());
  }

  /// The blockers of pair (s, t), appended to the last list of `lists`: the candidates meeting
  /// conv(S, T) seen from S (w.seen flags) or from T, taken from the grid or, when the pair is one
  /// of a group, from the candidates of the group's shaft (a superset of the grid's answer for
  /// the pair, but for patches that miss conv(S, T) by twice the tolerance). Stops at a blocker
  /// that hides all of T from all of S (single_occluder.h): the pair is then INVISIBLE, though the
  /// portal searches could not tell (an occluder inside a cell, a search past its budget): returns
  /// that blocker; or kWallHider when blockers in one plane hide it together (hiddenByWall); or
  /// kNoHider.
  uint32_t addBlockers(BlockerWorker& w, uint32_t s, uint32_t t,
                       const std::optional<std::span<const uint32_t>>& group,
                       BlockerLists& lists) const {
    const ConvexPolygon& sp = scene_.patches[s].polygon;
    const ConvexPolygon& tp = scene_.patches[t].polygon;
    const double margin = 2 * tol_.planeOffset();
    uint32_t hidden = kNoHider;
    const PairHull hull(sp, tp, tol_);
    Aabb box = patchBoxes_[s];
    box.add(patchBoxes_[t]);
    // The slack is PairHull's box tolerance: the grid does PairHull's box test, and the group's
    // candidates get the grid's tests.
    size_t count = 0;
    if (group) {
      // The group's candidates are sorted, so these are.
      for (uint32_t c : *group) {
        w.gathered[count] = c;
        count += box.meets(patchBoxes_[c], tol_.length());
      }
      count = hull.keepUnseparated(w.gathered.data(), count, patchBoxes_);
    } else {
      count = grid_->gatherInto(box, tol_.length(), w.gathered.data(), &hull);
      sortIds(std::span<uint32_t>(w.gathered.data(), count), w.bits);  // blockers come out sorted
    }
    const std::span<uint32_t> candidates(w.gathered.data(), count);
    const auto& b = seen_[t].seen;
    // Seen from T: a bit of its row when the rows are kept; else by flags when there are many
    // candidates to ask about (setting them costs a pass over seen(T)), else by searches in the
    // sorted seen(T).
    const uint64_t* rowT = seenBits_.empty() ? nullptr : seenBits_.data() + size_t(t) * seenWords_;
    const bool flagT = !rowT && candidates.size() * kFlagsPerSearch > b.size();
    if (flagT)
      for (uint32_t entry : b) w.seen[seenPatch(entry)] |= kFromT;
    auto fromT = b.begin();  // candidates rise: each search starts where the last ended
    w.between.clear();
    w.betweenOutlines.clear();
    for (uint32_t c : candidates) {
      if (c == s || c == t) continue;
      if (!w.seen[c]) {  // not seen from S (nor, with flags, from T)
        if (rowT) {
          if (!((rowT[c >> 6] >> (c & 63)) & 1)) continue;
        } else if (flagT) {
          continue;
        } else {
          fromT = std::lower_bound(fromT, b.end(), seenEntry(c, 0));
          if (fromT == b.end() || seenPatch(*fromT) != c) continue;
        }
      }
      const std::span<const Vec3> cv(vertices_.data() + vertexStart_[c],
                                     vertices_.data() + vertexStart_[c + 1]);
      if (hull.meetsInBox(cv, normals_[c], normalLengths_[c])) {
        if (between(w, c, s, t, margin)) {
          if (crossesInside(c, sp, tp, margin)) {
            hidden = c;
            break;
          }
          w.between.push_back(c);
          w.betweenOutlines.push_back(
              {&scene_.patches[c].polygon.plane, scene_.patches[c].polygon.vertices});
        }
        lists.addBlocker(c);
      }
    }
    if (hidden == kNoHider && hiddenByWall(w, s, t)) hidden = kWallHider;
    if (flagT)
      for (uint32_t entry : b) w.seen[seenPatch(entry)] &= kFromS;
    return hidden;
  }

  const Scene& scene_;
  const std::vector<PatchSearchResult>& seen_;
  Tolerance tol_;
  size_t n_;
  std::vector<Aabb> patchBoxes_;
  std::optional<PatchGrid> grid_;
  std::vector<uint32_t> vertexStart_;
  std::vector<Vec3> vertices_;
  std::vector<Vec3> normals_;
  std::vector<double> normalLengths_;
  std::vector<OccluderSlab> slabs_;   ///< per patch, as a blocker that may hide a pair whole
  std::vector<InwardEdge> edges_;     ///< per patch, from vertexStart_: inwardEdges
  std::vector<uint8_t> edgesUsable_;  ///< per patch: no edge of zero length
  std::vector<uint64_t> seenStart_;
  size_t seenWords_ = 0;
  /// Row p (seenWords_ words): the patches of seen(p); empty above kMaxSeenBitsPatches.
  std::vector<uint64_t> seenBits_;
  /// Row p: the patches whose front p's search saw (kSeenFront); empty with seenBits_.
  std::vector<uint64_t> frontBits_;
};

/// Chunks of kSeenPerChunk seen-list entries through a pipeline: worked on in parallel and
/// handed on (to the sink or into the graph) one at a time in order, so the output is (s, r)
/// sorted whatever the schedule, and with a sink only the chunks in flight are held: each is at
/// most kSeenPerChunk pairs, a source that saw many patches being cut into several. Chunks are
/// reused (no allocation once their arrays have grown), unless they grew past kKeptIdsPerChunk.
/// Returns the partial pairs in order (for the shaft sample).
std::vector<std::pair<uint32_t, uint32_t>> runBlockerPipeline(const BlockerDetection& detection,
                                                              int threads,
                                                              const PropagationOptions& options,
                                                              VisibilityGraph& graph) {
  VisibilityStats& st = graph.stats;
  const size_t n = detection.patchCount();
  const std::vector<uint64_t>& seenStart = detection.seenStart();
  tbb::enumerable_thread_specific<BlockerWorker> blockerWorkers(
      [&detection] { return detection.makeWorker(); });
  std::vector<std::unique_ptr<Chunk>> chunks;  // every chunk made (touched by the first stage)
  tbb::concurrent_queue<Chunk*> freeChunks;    // handed back by the last stage
  std::vector<std::pair<uint32_t, uint32_t>> partialPairs;  // in order, for the shaft sample
  uint64_t blockerSum = 0;
  uint64_t nextPosition = 0;
  size_t sourcesReported = 0;
  {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      tbb::parallel_pipeline(
          kChunksInFlightPerThread * size_t(threads),
          tbb::make_filter<void, Chunk*>(
              tbb::filter_mode::serial_in_order,
              [&](tbb::flow_control& fc) -> Chunk* {
                if (nextPosition >= seenStart[n]) {
                  fc.stop();
                  return nullptr;
                }
                Chunk* chunk = nullptr;
                if (!freeChunks.try_pop(chunk)) {
                  chunks.push_back(std::make_unique<Chunk>());
                  chunk = chunks.back().get();
                }
                chunk->begin = nextPosition;
                chunk->end = nextPosition = std::min(seenStart[n], nextPosition + kSeenPerChunk);
                // Sources s with seenStart[s + 1] <= end.
                chunk->sourcesDone =
                    size_t(std::upper_bound(seenStart.begin() + 1, seenStart.end(), chunk->end) -
                           (seenStart.begin() + 1));
                return chunk;
              }) &
              tbb::make_filter<Chunk*, Chunk*>(tbb::filter_mode::parallel,
                                               [&](Chunk* chunk) {
                                                 if (options.deadline != Clock::time_point::max() &&
                                                     Clock::now() > options.deadline)
                                                   throw PropagationDeadlineExceeded();
                                                 detection.fill(blockerWorkers.local(), *chunk);
                                                 return chunk;
                                               }) &
              tbb::make_filter<Chunk*, void>(tbb::filter_mode::serial_in_order, [&](Chunk* chunk) {
                const BlockerLists& lists = chunk->lists;
                st.pairsVisible += chunk->visible;
                st.pairsPartial += chunk->partial;
                st.sameCellShortcuts += chunk->sameCell;
                st.pairsHiddenByOne += chunk->hidden;
                st.pairsHiddenByWall += chunk->hiddenByWall;
                blockerSum += lists.idCount();
                for (size_t k = 0; k < lists.size(); ++k)
                  if (!lists.blockers(k).empty()) partialPairs.emplace_back(lists.s(k), lists.r(k));
                if (options.interactionSink) {
                  options.interactionSink(lists);
                } else {
                  for (size_t k = 0; k < lists.size(); ++k) {
                    const auto ids = lists.blockers(k);
                    graph.interactions.push_back(
                        {lists.s(k), lists.r(k), std::vector<uint32_t>(ids.begin(), ids.end())});
                  }
                }
                if (options.blockerProgress && chunk->sourcesDone > sourcesReported)
                  options.blockerProgress(sourcesReported = chunk->sourcesDone, n);
                if (chunk->lists.idCapacity() > kKeptIdsPerChunk) chunk->lists = {};
                chunk->lists.clear();
                chunk->visible = chunk->partial = chunk->sameCell = chunk->hidden =
                    chunk->hiddenByWall = 0;
                freeChunks.push(chunk);
              }));
    });
  }
  if (options.blockerProgress && sourcesReported < n) options.blockerProgress(n, n);
  st.meanBlockersPerPartial = st.pairsPartial ? double(blockerSum) / double(st.pairsPartial) : 0;
  return partialPairs;
}

/// Shaft-culling baseline (Haines & Wallace): every patch meeting conv(S, R), on a sample of the
/// partial pairs.
void sampleShaftCulling(const Scene& scene, const std::vector<Aabb>& patchBoxes,
                        const std::vector<std::pair<uint32_t, uint32_t>>& partialPairs,
                        const Tolerance& tol, const PropagationOptions& options,
                        VisibilityStats& st) {
  const size_t n = scene.patches.size();
  if (st.pairsPartial > 0 && options.shaftSamples > 0) {
    const uint64_t stride = std::max<uint64_t>(1, st.pairsPartial / options.shaftSamples);
    uint64_t k = 0, sum = 0;
    for (const auto& [ps, pr] : partialPairs) {
      if ((k++ % stride) != 0) continue;
      const PairHull hull(scene.patches[ps].polygon, scene.patches[pr].polygon, tol);
      for (uint32_t c = 0; c < n; ++c)
        if (c != ps && c != pr && hull.meets(scene.patches[c].polygon, patchBoxes[c])) ++sum;
      ++st.shaftSamples;
    }
    st.meanShaftCullPerPartial = double(sum) / double(st.shaftSamples);
  }
}

}  // namespace

void detectBlockers(const Scene& scene, const std::vector<PatchSearchResult>& seen,
                    const Tolerance& tol, int threads, const PropagationOptions& options,
                    VisibilityGraph& graph) {
  const auto blockerStart = Clock::now();
  const BlockerDetection detection(scene, seen, tol);
  const std::vector<std::pair<uint32_t, uint32_t>> partialPairs =
      runBlockerPipeline(detection, threads, options, graph);
  graph.stats.blockerSeconds = secondsSince(blockerStart);
  sampleShaftCulling(scene, detection.patchBoxes(), partialPairs, tol, options, graph.stats);
}

}  // namespace gv
