// Patches cut along the outlines of parallel patches resting on them or hanging just in front.
#include "scene/contact_split.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include "geometry/box_sweep.h"
#include "util/fnv_hash.h"

namespace gv {
namespace {

/// A merged polygon may turn by at most this (the sine of the angle) the wrong way at a vertex:
/// rounding of cut points, far below anything that makes a polygon visibly non-convex.
constexpr double kMergeConvexity = 1e-9;

/// Twice the area over the longest edge: the polygon's narrowest extent, up to a factor 2.
double width(const ConvexPolygon& p) {
  double longest = 0;
  for (size_t i = 0; i < p.vertices.size(); ++i)
    longest = std::max(longest, length(p.vertices[(i + 1) % p.vertices.size()] - p.vertices[i]));
  return longest > 0 ? 2 * p.area() / longest : 0;
}

/// Largest gap at which patch q still shadows a patch (kContactShadowGapRatio).
double maxGap(const ConvexPolygon& q) {
  return kContactShadowGapRatio * std::sqrt(q.area());
}

/// True when q is parallel to p and lies in p's plane or in front of it within maxGap(q).
bool shadows(const ConvexPolygon& q, const ConvexPolygon& p, const Tolerance& tol) {
  if (1 - std::abs(dot(q.normal(), p.normal())) > tol.normalCos()) return false;
  const double gap = maxGap(q);
  for (const Vec3& v : q.vertices) {
    const double d = p.plane.distance(v);
    if (d < -tol.planeOffset() || d > gap + tol.planeOffset()) return false;
  }
  return true;
}

/// The side planes of q's outline seen along p's normal: perpendicular to p through each edge of
/// q projected onto p's plane, each with q's inside at its back.
std::vector<Plane> outlinePlanes(const ConvexPolygon& q, const Plane& onto) {
  std::vector<Vec3> v;
  for (const Vec3& x : q.vertices) v.push_back(x - onto.distance(x) * onto.normal);
  const Vec3 inside = q.centroid() - onto.distance(q.centroid()) * onto.normal;
  std::vector<Plane> planes;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 a = v[i], b = v[(i + 1) % v.size()];
    const Vec3 n = cross(b - a, onto.normal);
    if (length(n) == 0) continue;
    Plane side = Plane::through(a, n);
    if (side.distance(inside) > 0) side = side.flipped();
    planes.push_back(side);
  }
  return planes;
}

/// Cuts `x` along the outline `planes`: the pieces outside the outline, then the one inside.
/// Returns {x} itself when x does not overlap the outline's inside, or when every cut would leave
/// a piece narrower than `minWidth` (such a cut is skipped; the pieces still tile x).
std::vector<ConvexPolygon> cutAlongOutline(const ConvexPolygon& x, const std::vector<Plane>& planes,
                                           double minWidth, const Tolerance& tol) {
  std::vector<ConvexPolygon> pieces;
  ConvexPolygon rest = x;
  for (const Plane& plane : planes) {
    PolygonSplit s = split(rest, plane, tol);
    if (!s.front) continue;   // rest is inside this side
    if (!s.back) return {x};  // rest (so x) is outside the outline
    if (width(*s.front) < minWidth || width(*s.back) < minWidth) continue;
    pieces.push_back(std::move(*s.front));
    rest = std::move(*s.back);
  }
  if (pieces.empty()) return {x};
  pieces.push_back(std::move(rest));
  return pieces;
}

/// Pairs (p, q) with q shadowing p, from a sweep along x over boxes grown by q's gap.
std::vector<std::vector<uint32_t>> shadowingPatches(const Scene& scene, const Tolerance& tol) {
  const size_t n = scene.patches.size();
  std::vector<Aabb> boxes(n);
  for (size_t i = 0; i < n; ++i) {
    const ConvexPolygon& poly = scene.patches[i].polygon;
    boxes[i] = poly.bounds().grown(maxGap(poly) + tol.planeOffset());
  }
  std::vector<std::vector<uint32_t>> shadowsOf(n);
  forEachOverlappingBoxPair(boxes, 0.0, [&](uint32_t a, uint32_t b) {
    const ConvexPolygon& pa = scene.patches[a].polygon;
    const ConvexPolygon& pb = scene.patches[b].polygon;
    if (shadows(pb, pa, tol)) shadowsOf[a].push_back(b);
    if (shadows(pa, pb, tol)) shadowsOf[b].push_back(a);
  });
  for (auto& s : shadowsOf) std::sort(s.begin(), s.end());
  return shadowsOf;
}

bool boxesOverlap(const Aabb& a, const Aabb& b, double eps) {
  for (int axis = 0; axis < 3; ++axis)
    if (a.lo[axis] > b.hi[axis] + eps || b.lo[axis] > a.hi[axis] + eps) return false;
  return true;
}

/// The union of convex polygons x and y when they share a whole edge (y's runs the other way)
/// and the union is convex; nullopt otherwise.
std::optional<ConvexPolygon> mergeAlongEdge(const ConvexPolygon& x, const ConvexPolygon& y,
                                            const Tolerance& tol) {
  const size_t n = x.vertices.size(), m = y.vertices.size();
  const double eps = tol.length();
  for (size_t i = 0; i < n; ++i) {
    const Vec3& a = x.vertices[i];
    const Vec3& b = x.vertices[(i + 1) % n];
    for (size_t j = 0; j < m; ++j) {
      if (distance(y.vertices[j], b) > eps || distance(y.vertices[(j + 1) % m], a) > eps) continue;
      std::vector<Vec3> v;
      for (size_t k = 0; k < n; ++k) v.push_back(x.vertices[(i + 1 + k) % n]);  // b .. a
      for (size_t k = 0; k + 2 < m; ++k) v.push_back(y.vertices[(j + 2 + k) % m]);
      for (size_t k = 0; k < v.size(); ++k) {
        const Vec3 e1 = v[(k + 1) % v.size()] - v[k];
        const Vec3 e2 = v[(k + 2) % v.size()] - v[(k + 1) % v.size()];
        if (dot(cross(e1, e2), x.plane.normal) < -kMergeConvexity * length(e1) * length(e2))
          return std::nullopt;
      }
      return ConvexPolygon::fromVerticesInPlane(std::move(v), x.plane, tol);
    }
  }
  return std::nullopt;
}

/// Merges pieces that lie under the same shadows (by their centroids against the `outlines`,
/// whose boxes are `reaches`)
/// where two share a whole edge and their union is convex, until no two do. Cutting along one
/// outline after another runs each cut across the whole piece it meets (a wall's footprint cuts
/// the storey's slab from end to end), so the open floor comes out in strips that merging
/// joins back into rooms.
void mergePieces(std::vector<ConvexPolygon>& pieces,
                 const std::vector<std::vector<Plane>>& outlines, const std::vector<Aabb>& reaches,
                 const Tolerance& tol) {
  std::vector<std::vector<uint32_t>> under(pieces.size());
  for (size_t i = 0; i < pieces.size(); ++i) {
    const Vec3 c = pieces[i].centroid();
    for (uint32_t o = 0; o < outlines.size(); ++o) {
      if (!boxesOverlap(Aabb{c, c}, reaches[o], 0)) continue;
      bool inside = true;
      for (const Plane& plane : outlines[o]) inside = inside && plane.distance(c) <= 0;
      if (inside) under[i].push_back(o);
    }
  }
  // Candidates: pieces with an edge running the other way between the same two points (the two
  // sides of one cut carry bit-identical cut points).
  const auto key = [](const Vec3& a, const Vec3& b) {
    Fnv1a h;
    for (const Vec3& v : {a, b}) h.bytes(&v, sizeof v);
    return h.value();
  };
  std::vector<bool> alive(pieces.size(), true);
  for (bool merged = true; merged;) {
    merged = false;
    std::unordered_multimap<uint64_t, size_t> edges;
    for (size_t i = 0; i < pieces.size(); ++i) {
      if (!alive[i]) continue;
      const auto& v = pieces[i].vertices;
      for (size_t k = 0; k < v.size(); ++k) edges.emplace(key(v[k], v[(k + 1) % v.size()]), i);
    }
    for (size_t i = 0; i < pieces.size(); ++i) {
      for (size_t k = 0; alive[i] && k < pieces[i].vertices.size(); ++k) {
        const auto& v = pieces[i].vertices;
        const auto [lo, hi] = edges.equal_range(key(v[(k + 1) % v.size()], v[k]));
        for (auto it = lo; it != hi; ++it) {
          const size_t j = it->second;
          if (j == i || !alive[j] || under[j] != under[i]) continue;
          std::optional<ConvexPolygon> u = mergeAlongEdge(pieces[i], pieces[j], tol);
          if (!u) continue;
          pieces[i] = std::move(*u);
          alive[j] = false;
          merged = true;
          k = static_cast<size_t>(-1);  // piece i changed: look at its new edges from the start
          break;
        }
      }
    }
  }
  std::vector<ConvexPolygon> kept;
  for (size_t i = 0; i < pieces.size(); ++i)
    if (alive[i]) kept.push_back(std::move(pieces[i]));
  pieces = std::move(kept);
}

}  // namespace

ContactSplitReport splitPatchesAtContacts(Scene& scene) {
  ContactSplitReport report;
  if (scene.patches.empty()) return report;
  const Tolerance tol = scene.tolerance();
  const double minWidth = kContactMinPieceWidth * tol.scale;
  const std::vector<std::vector<uint32_t>> shadowsOf = shadowingPatches(scene, tol);
  std::vector<Patch> out;
  out.reserve(scene.patches.size());
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const Patch& patch = scene.patches[p];
    std::vector<ConvexPolygon> pieces{patch.polygon};
    std::vector<Aabb> boxes{patch.polygon.bounds()};
    std::vector<std::vector<Plane>> outlines;
    std::vector<Aabb> reaches;
    for (uint32_t q : shadowsOf[p]) {
      const ConvexPolygon& caster = scene.patches[q].polygon;
      outlines.push_back(outlinePlanes(caster, patch.polygon.plane));
      const std::vector<Plane>& planes = outlines.back();
      // q's outline projected onto p's plane has q's in-plane extent: its box grown along
      // p's normal by the gap meets every piece q overlaps.
      Aabb reach = caster.bounds();
      const double gap = maxGap(caster) + tol.planeOffset();
      reach.lo = reach.lo - gap * Vec3{1, 1, 1};
      reach.hi = reach.hi + gap * Vec3{1, 1, 1};
      reaches.push_back(reach);
      // Pieces are cut in place: the first part keeps the slot, the others are appended.
      for (size_t i = 0, n = pieces.size(); i < n; ++i) {
        if (!boxesOverlap(boxes[i], reach, tol.length())) continue;
        std::vector<ConvexPolygon> cut = cutAlongOutline(pieces[i], planes, minWidth, tol);
        if (cut.size() == 1) continue;
        for (size_t k = 0; k < cut.size(); ++k) {
          const Aabb box = cut[k].bounds();
          if (k == 0) {
            pieces[i] = std::move(cut[k]);
            boxes[i] = box;
          } else {
            pieces.push_back(std::move(cut[k]));
            boxes.push_back(box);
          }
        }
      }
    }
    if (pieces.size() > 1) mergePieces(pieces, outlines, reaches, tol);
    if (pieces.size() > 1) {
      ++report.patchesSplit;
      report.piecesMade += pieces.size();
    }
    for (ConvexPolygon& piece : pieces)
      out.push_back({std::move(piece), patch.material, patch.sourceFace});
  }
  scene.patches = std::move(out);
  scene.report.splitAtContacts += report.patchesSplit;
  scene.report.contactPieces += report.piecesMade;
  return report;
}

}  // namespace gv
