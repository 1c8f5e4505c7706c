// Independent checks for the spatial subdivision (paper §3): point-in-polygon, segment-vs-patch
// and the invariants every Subdivision must satisfy, by sampling and brute force. Written for
// the tests from scratch; uses only the plain data of the Subdivision, none of src/bsp's logic.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <random>
#include <set>
#include <vector>

#include "bsp/subdivision.h"
#include "generators/scene_builder.h"
#include "scene/scene.h"
#include "support/oracle_math.h"

namespace gv::bsptest {

using test::uniform;

/// Unit normal of a polygon from its fan triangle sum (Newell).
inline Vec3 normalOf(const std::vector<Vec3>& v) {
  const Vec3 n = test::vectorArea2(v);
  return n / length(n);
}

inline double areaOf(const std::vector<Vec3>& v) { return 0.5 * length(test::vectorArea2(v)); }

/// Smallest signed distance from p (projected into the polygon's plane) to the polygon's edges,
/// positive inside. The polygon is convex, either orientation.
inline double insideDepth(const std::vector<Vec3>& v, const Vec3& p) {
  const Vec3 n = normalOf(v);
  double depth = INFINITY;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 e = v[(i + 1) % v.size()] - v[i];
    const Vec3 inward = normalize(cross(n, e));
    depth = std::min(depth, dot(inward, p - v[i]));
  }
  return depth;
}

/// True when p lies within `off` of the polygon's plane and at least `margin` inside its edges
/// (a negative margin accepts points up to -margin outside).
inline bool inPolygon(const std::vector<Vec3>& v, const Vec3& p, double margin, double off) {
  const Vec3 n = normalOf(v);
  return std::abs(dot(n, p - v[0])) <= off && insideDepth(v, p) >= margin;
}

/// A random point of a convex polygon (fan triangle by area, then uniform in it).
inline Vec3 samplePolygon(const std::vector<Vec3>& v, std::mt19937& rng) {
  std::vector<double> w;
  double total = 0;
  for (size_t i = 1; i + 1 < v.size(); ++i) {
    total += length(cross(v[i] - v[0], v[i + 1] - v[0]));
    w.push_back(total);
  }
  const double pick = uniform(rng, 0, total);
  size_t t = 0;
  while (t + 1 < w.size() && w[t] < pick) ++t;
  double a = uniform(rng, 0, 1), b = uniform(rng, 0, 1);
  if (a + b > 1) a = 1 - a, b = 1 - b;
  return v[0] + (v[t + 1] - v[0]) * a + (v[t + 2] - v[0]) * b;
}

/// True when the segment a-b passes through the patch or within `margin` of it.
inline bool segmentNearPatch(const Vec3& a, const Vec3& b, const Patch& patch, double margin) {
  const std::vector<Vec3>& v = patch.polygon.vertices;
  const Vec3 n = normalOf(v);
  const double da = dot(n, a - v[0]), db = dot(n, b - v[0]);
  if ((da > margin && db > margin) || (da < -margin && db < -margin)) return false;
  // Check the points of the segment within `margin` of the plane: the crossing point, or the
  // whole sub-segment when it runs (nearly) along the plane.
  const int steps = std::abs(da - db) < 4 * margin ? 64 : 1;
  for (int s = 0; s <= steps; ++s) {
    Vec3 p;
    if (steps == 1) {
      const double t = std::clamp(da / (da - db), 0.0, 1.0);
      p = a + (b - a) * t;
    } else {
      p = a + (b - a) * (static_cast<double>(s) / steps);
    }
    if (std::abs(dot(n, p - v[0])) <= 2 * margin && insideDepth(v, p) >= -2 * margin) return true;
  }
  return false;
}

/// The cells strictly containing p (at least `margin` inside every halfspace).
inline int cellsStrictlyContaining(const Subdivision& sub, const Vec3& p, double margin) {
  int count = 0;
  for (const Cell& c : sub.cells) {
    const bool in = std::all_of(c.shape.halfspaces.begin(), c.shape.halfspaces.end(),
                                [&](const Plane& h) { return h.distance(p) < -margin; });
    count += in;
  }
  return count;
}

/// Cells reachable from `start` through portals (breadth first).
inline std::vector<bool> reachable(const Subdivision& sub, uint32_t start) {
  std::vector<bool> seen(sub.cells.size(), false);
  std::deque<uint32_t> queue{start};
  seen[start] = true;
  while (!queue.empty()) {
    const uint32_t c = queue.front();
    queue.pop_front();
    for (uint32_t p : sub.cells[c].portals) {
      const uint32_t o = sub.portals[p].other(c);
      if (!seen[o]) seen[o] = true, queue.push_back(o);
    }
  }
  return seen;
}

/// The first cell whose halfspaces hold p with `margin` to spare (brute force); -1 if none.
inline int cellStrictlyAt(const Subdivision& sub, const Vec3& p, double margin) {
  for (size_t i = 0; i < sub.cells.size(); ++i) {
    const auto& hs = sub.cells[i].shape.halfspaces;
    if (std::all_of(hs.begin(), hs.end(), [&](const Plane& h) { return h.distance(p) < -margin; }))
      return static_cast<int>(i);
  }
  return -1;
}

/// Patches whose plane holds polygon `v` (within `off`), either facing.
inline std::vector<uint32_t> coplanarPatches(const Scene& scene, const std::vector<Vec3>& v,
                                             double off) {
  std::vector<uint32_t> out;
  const Vec3 n = normalOf(v);
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    const auto& pv = scene.patches[i].polygon.vertices;
    if (std::abs(dot(normalOf(pv), n)) < 1 - 1e-6) continue;
    const bool on = std::all_of(pv.begin(), pv.end(),
                                [&](const Vec3& q) { return std::abs(dot(n, q - v[0])) <= off; });
    if (on) out.push_back(i);
  }
  return out;
}

/// The root volume: the box of all cell vertices.
inline Aabb cellsBounds(const Subdivision& sub) {
  Aabb box;
  for (const Cell& c : sub.cells)
    for (const auto& f : c.shape.faces)
      for (const Vec3& v : f.polygon.vertices) box.add(v);
  return box;
}

/// Every invariant of issue #3, checked by sampling with `samples` random draws per check.
inline void expectInvariants(const Scene& scene, const Subdivision& sub, uint32_t seed,
                             int samples = 400) {
  std::mt19937 rng(seed);
  ASSERT_FALSE(sub.cells.empty());
  Aabb scn = scene.bounds();
  const double scale = scn.diagonal();
  const double margin = 1e-7 * scale;  // far above the library's 1e-9 length tolerance
  // The library merges planes closer than 1e-5 of the scene (its model tolerance): a patch
  // within half that of a face must block it, one within twice that may.
  const double mustOff = 0.5e-5 * scale, mayOff = 2e-5 * scale;
  const Aabb root = cellsBounds(sub);

  // 1. The cells' volumes sum to the root box's volume.
  double volume = 0;
  for (const Cell& c : sub.cells) {
    const double v = c.shape.volume();
    EXPECT_GT(v, 0);
    volume += v;
  }
  const Vec3 e = root.extent();
  EXPECT_NEAR(volume, e.x * e.y * e.z, 1e-8 * e.x * e.y * e.z);

  // 2. Random points of the root lie in exactly one cell: at most one strictly, at least one
  //    loosely.
  for (int i = 0; i < samples; ++i) {
    const Vec3 p{uniform(rng, root.lo.x, root.hi.x), uniform(rng, root.lo.y, root.hi.y),
                 uniform(rng, root.lo.z, root.hi.z)};
    EXPECT_LE(cellsStrictlyContaining(sub, p, margin), 1) << p;
    EXPECT_GE(cellsStrictlyContaining(sub, p, -margin), 1) << p;
  }

  // 3. Portals: link two different cells, lie on the boundary of both (in a face of each, facing
  //    the right way), and no point of a portal is inside a coplanar patch.
  for (size_t k = 0; k < sub.portals.size(); ++k) {
    const Portal& portal = sub.portals[k];
    const auto& pv = portal.polygon.vertices;
    ASSERT_NE(portal.back, portal.front);
    const Vec3 n = normalOf(pv);
    const Vec3 c = portal.polygon.centroid();
    for (auto [cell, outward] : {std::pair{portal.back, n}, std::pair{portal.front, -n}}) {
      const ConvexPolyhedron& s = sub.cells[cell].shape;
      bool onFace = false;
      for (const PolyhedronFace& f : s.faces) {
        const auto& fv = f.polygon.vertices;
        if (dot(normalOf(fv), outward) < 1 - 1e-9) continue;
        bool all = true;
        for (const Vec3& q : pv) all = all && inPolygon(fv, q, -margin, margin);
        onFace = onFace || all;
      }
      EXPECT_TRUE(onFace) << "portal " << k << " is not on a face of cell " << cell;
    }
    const std::vector<uint32_t> coplanar = coplanarPatches(scene, pv, mustOff);
    for (int i = 0; i < 8; ++i) {
      // Pull samples a little toward the centroid so that they are clear of the edges.
      const Vec3 q = c + (samplePolygon(pv, rng) - c) * 0.999;
      if (insideDepth(pv, q) < margin) continue;
      for (uint32_t patch : coplanar) {
        EXPECT_FALSE(inPolygon(scene.patches[patch].polygon.vertices, q, margin, 2 * mustOff))
            << "portal " << k << " overlaps patch " << patch << " at " << q;
      }
    }
  }

  // 4. On every inner boundary face, portals and coaffine patches tile it: a point clear of all
  //    edges is in exactly one portal or in a patch, never both; the portal areas never exceed
  //    the face's and equal it when no patch lies on the face.
  for (size_t ci = 0; ci < sub.cells.size(); ++ci) {
    const Cell& cell = sub.cells[ci];
    for (size_t fi = 0; fi < cell.faces.size(); ++fi) {
      const BoundaryFace& bf = cell.faces[fi];
      const auto& fv = cell.shape.faces[fi].polygon.vertices;
      if (bf.node < 0) {
        EXPECT_TRUE(bf.portals.empty());
        continue;
      }
      const std::vector<uint32_t> must = coplanarPatches(scene, fv, mustOff);
      const std::vector<uint32_t> coplanar = coplanarPatches(scene, fv, mayOff);
      double portalArea = 0;
      for (uint32_t p : bf.portals) portalArea += areaOf(sub.portals[p].polygon.vertices);
      const double faceArea = areaOf(fv);
      EXPECT_LE(portalArea, faceArea * (1 + 1e-9) + margin * scale);
      if (coplanar.empty()) {
        EXPECT_NEAR(portalArea, faceArea, 1e-7 * faceArea + margin * scale);
      }
      for (int i = 0; i < 6; ++i) {
        const Vec3 q = samplePolygon(fv, rng);
        if (insideDepth(fv, q) < margin) continue;
        int strictPortals = 0, loosePortals = 0;
        for (uint32_t p : bf.portals) {
          strictPortals += inPolygon(sub.portals[p].polygon.vertices, q, margin, margin);
          loosePortals += inPolygon(sub.portals[p].polygon.vertices, q, -margin, margin);
        }
        bool strictPatch = false, loosePatch = false;
        for (uint32_t patch : must) {
          strictPatch = strictPatch ||
                        inPolygon(scene.patches[patch].polygon.vertices, q, margin, 2 * mustOff);
        }
        for (uint32_t patch : coplanar) {
          loosePatch = loosePatch ||
                       inPolygon(scene.patches[patch].polygon.vertices, q, -margin, 2 * mayOff);
        }
        EXPECT_LE(strictPortals, 1) << "overlapping portals at " << q;
        EXPECT_FALSE(strictPortals > 0 && strictPatch) << "portal over a patch at " << q;
        EXPECT_TRUE(loosePortals > 0 || loosePatch)
            << "cell " << ci << " face " << fi << ": point " << q << " neither portal nor patch";
        // Every patch listed as coaffine really is coplanar with the face.
        for (uint32_t patch : bf.coaffinePatches) {
          EXPECT_TRUE(std::find(coplanar.begin(), coplanar.end(), patch) != coplanar.end())
              << "patch " << patch << " listed on cell " << ci << " face " << fi;
        }
      }
    }
  }
}

/// Random segments in the root that pass no patch (brute force) may go from one cell to the next
/// only through a portal linking the two that holds the crossing point. Returns how many cell
/// boundary crossings were checked (so a test can insist the check was not vacuous).
inline int expectSegmentsCrossOnlyThroughPortals(const Scene& scene, const Subdivision& sub,
                                                 uint32_t seed, int segments) {
  std::mt19937 rng(seed);
  const double scale = scene.bounds().diagonal();
  const double margin = 1e-7 * scale;
  const Aabb root = cellsBounds(sub);
  int crossings = 0;
  for (int s = 0; s < segments; ++s) {
    auto point = [&] {
      return Vec3{uniform(rng, root.lo.x, root.hi.x), uniform(rng, root.lo.y, root.hi.y),
                  uniform(rng, root.lo.z, root.hi.z)};
    };
    const Vec3 a = point();
    // Short segments mostly: long ones nearly always hit a patch in a dense scene.
    const Vec3 b = a + (point() - a) * uniform(rng, 0.02, 0.5);
    bool blocked = false;
    for (const Patch& p : scene.patches)
      blocked = blocked || segmentNearPatch(a, b, p, 10 * margin);
    if (blocked) continue;
    // Each cell's parameter interval along the segment (clip by its halfspaces).
    struct Span {
      double t0, t1;
      uint32_t cell;
    };
    std::vector<Span> spans;
    for (uint32_t c = 0; c < sub.cells.size(); ++c) {
      double t0 = 0, t1 = 1;
      for (const Plane& h : sub.cells[c].shape.halfspaces) {
        const double da = h.distance(a), db = h.distance(b);
        if (da > 0 && db > 0) t1 = -1;
        if (da > 0 && db <= 0) t0 = std::max(t0, da / (da - db));
        if (da <= 0 && db > 0) t1 = std::min(t1, da / (da - db));
      }
      if (t1 - t0 > 0) spans.push_back({t0, t1, c});
    }
    std::sort(spans.begin(), spans.end(), [](const Span& x, const Span& y) { return x.t0 < y.t0; });
    const double len = distance(a, b);
    const double tm = 100 * margin / len;  // parameter slack
    // Skip segments that graze a cell edge: a span so short, or three cells meeting at one t.
    bool ambiguous = false;
    for (size_t i = 0; i < spans.size(); ++i) {
      if (spans[i].t1 - spans[i].t0 < tm) ambiguous = true;
      if (i + 1 < spans.size() && std::abs(spans[i].t1 - spans[i + 1].t0) > tm) ambiguous = true;
    }
    if (ambiguous || spans.empty()) continue;
    for (size_t i = 0; i + 1 < spans.size(); ++i) {
      const uint32_t from = spans[i].cell, to = spans[i + 1].cell;
      const Vec3 x = a + (b - a) * (0.5 * (spans[i].t1 + spans[i + 1].t0));
      bool through = false;
      for (uint32_t p : sub.cells[from].portals) {
        const Portal& portal = sub.portals[p];
        if (portal.other(from) != to) continue;
        through = through || inPolygon(portal.polygon.vertices, x, -10 * margin, 10 * margin);
      }
      EXPECT_TRUE(through) << "segment " << a << " -> " << b << " crosses from cell " << from
                           << " to " << to << " at " << x << " outside every portal";
      ++crossings;
    }
  }
  return crossings;
}

}  // namespace gv::bsptest
