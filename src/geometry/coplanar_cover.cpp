// Coverage of the crossing hull of two polygons by coplanar blockers. Beyond paper §6.2 (Fig. 17).
#include "geometry/coplanar_cover.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gv {
namespace {

struct P2 {
  double x, y;
};
using Poly2 = std::vector<P2>;

double cross2(const P2& o, const P2& a, const P2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/// Counter-clockwise convex hull (Andrew's monotone chain); fewer than 3 points when degenerate.
Poly2 convexHull(std::vector<P2> pts) {
  std::sort(pts.begin(), pts.end(),
            [](const P2& a, const P2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (pts.size() < 3) return pts;
  Poly2 hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross2(hull[k - 2], hull[k - 1], pts[i - 1]) <= 0) --k;
    hull[k++] = pts[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

/// Twice the area over the longest edge: below `eps` the piece is thinner than the tolerance.
/// (Compared squared: this runs for every piece of every subtraction.)
bool thin(const Poly2& p, double eps) {
  if (p.size() < 3) return true;
  double area2 = 0, longest2 = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const P2& a = p[i];
    const P2& b = p[(i + 1) % p.size()];
    area2 += a.x * b.y - a.y * b.x;
    longest2 = std::max(longest2, (b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y));
  }
  return !(area2 * area2 > eps * eps * longest2);
}

/// The part of convex `in` where the signed distance to the directed line a → b (positive on
/// its left) is >= 0 when `left`, <= 0 otherwise. (The distance unnormalized: only its sign and
/// ratios are used.)
Poly2 clipHalfplane(const Poly2& in, const P2& a, const P2& b, bool left) {
  auto dist = [&](const P2& p) {
    const double d = cross2(a, b, p);
    return left ? d : -d;
  };
  Poly2 out;
  for (size_t i = 0; i < in.size(); ++i) {
    const P2& p = in[i];
    const P2& q = in[(i + 1) % in.size()];
    const double dp = dist(p), dq = dist(q);
    if (dp >= 0) out.push_back(p);
    if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) {
      const double t = dp / (dp - dq);
      out.push_back({p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t});
    }
  }
  return out;
}

}  // namespace

bool coplanarOutlinesCover(const ConvexPolygon& s, const ConvexPolygon& r,
                           std::span<const PlanarOutline> blockers, double eps) {
  if (blockers.empty()) return false;
  const Plane& plane = *blockers.front().plane;
  for (const PlanarOutline& b : blockers)
    for (const Vec3& v : b.vertices)
      if (std::abs(plane.distance(v)) > eps) return false;
  // Most groups fail here, cheaply and before anything is allocated (the blocker stage of `vis`
  // asks about every pair with two blockers in one plane between its ends): a point where a
  // segment between vertices of S and R crosses the plane, farther than eps outside every
  // blocker. (Inside: left of every edge seen from the blocker's own front, or within eps.)
  for (const Vec3& sv : s.vertices) {
    const double ds = plane.distance(sv);
    for (const Vec3& rv : r.vertices) {
      const double dr = plane.distance(rv);
      if (ds == dr) return false;  // both on the plane: degenerate, no conclusion
      const Vec3 x = sv + (rv - sv) * (ds / (ds - dr));
      bool inSome = false;
      for (const PlanarOutline& b : blockers) {
        const size_t m = b.vertices.size();
        inSome = true;
        for (size_t k = 0; k < m && inSome; ++k) {
          const Vec3& a = b.vertices[k];
          const Vec3 edge = b.vertices[k + 1 < m ? k + 1 : 0] - a;
          inSome = dot(cross(b.plane->normal, edge), x - a) >= -eps * length(edge);
        }
        if (inSome) break;
      }
      if (!inSome) return false;
    }
  }

  // A 2D frame of the plane.
  const Vec3 n = plane.normal;
  const Vec3 u = normalize(std::abs(n.x) < 0.9 ? cross(n, {1, 0, 0}) : cross(n, {0, 1, 0}));
  const Vec3 w = cross(n, u);  // (u, w, n) right-handed: counter-clockwise seen from the front
  const Vec3 origin = blockers.front().vertices.front();
  auto to2 = [&](const Vec3& p) { return P2{dot(p - origin, u), dot(p - origin, w)}; };

  // Where the segments between the vertices of S and of R cross the plane.
  std::vector<P2> crossings;
  for (const Vec3& sv : s.vertices) {
    const double ds = plane.distance(sv);
    for (const Vec3& rv : r.vertices) {
      const double dr = plane.distance(rv);
      crossings.push_back(to2(sv + (rv - sv) * (ds / (ds - dr))));
    }
  }
  const Poly2 hull = convexHull(crossings);
  if (hull.size() < 3) return false;

  // Boxes first: real levels put dozens of coplanar pieces of one wall in a group, most of
  // them nowhere near a given piece of the hull, and each subtraction multiplies the pieces.
  struct Box2 {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    void add(const P2& p) {
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x),
      y1 = std::max(y1, p.y);
    }
    bool overlaps(const Box2& o, double e) const {
      return x0 <= o.x1 + e && o.x0 <= x1 + e && y0 <= o.y1 + e && o.y0 <= y1 + e;
    }
  };
  auto boxOf = [](const Poly2& p) {
    Box2 b;
    for (const P2& q : p) b.add(q);
    return b;
  };
  std::vector<Poly2> remaining{hull}, next;
  for (const PlanarOutline& b : blockers) {
    Poly2 poly;  // in the frame, counter-clockwise there
    for (const Vec3& v : b.vertices) poly.push_back(to2(v));
    if (dot(b.plane->normal, n) < 0) std::reverse(poly.begin(), poly.end());
    const Box2 blockerBox = boxOf(poly);
    next.clear();
    for (Poly2& piece : remaining) {
      if (!boxOf(piece).overlaps(blockerBox, eps)) {
        next.push_back(std::move(piece));  // wholly outside this blocker: kept as it is
        continue;
      }
      // Subtract the convex blocker: what lies right of each edge is outside it (kept); the rest
      // goes on to the next edge; what is left of every edge is inside (removed).
      for (size_t k = 0; k < poly.size() && !piece.empty(); ++k) {
        const P2& a = poly[k];
        const P2& c = poly[(k + 1) % poly.size()];
        Poly2 outside = clipHalfplane(piece, a, c, false);
        if (!thin(outside, eps)) next.push_back(std::move(outside));
        piece = clipHalfplane(piece, a, c, true);
        if (thin(piece, eps)) piece.clear();
      }
    }
    remaining.swap(next);
    if (remaining.empty()) return true;
  }
  return false;
}

bool someCoplanarGroupCovers(const ConvexPolygon& s, const ConvexPolygon& r,
                             std::span<const PlanarOutline> outlines, double eps,
                             CoplanarGroups& scratch) {
  if (outlines.size() < 2) return false;
  scratch.grouped.assign(outlines.size(), 0);
  for (size_t i = 0; i + 1 < outlines.size(); ++i) {
    if (scratch.grouped[i]) continue;
    const Plane& plane = *outlines[i].plane;
    scratch.group.assign(1, outlines[i]);
    scratch.members.assign(1, uint32_t(i));
    for (size_t j = i + 1; j < outlines.size(); ++j) {
      if (scratch.grouped[j]) continue;
      bool on = true;
      for (size_t k = 0; k < outlines[j].vertices.size() && on; ++k)
        on = std::abs(plane.distance(outlines[j].vertices[k])) <= eps;
      if (!on) continue;
      scratch.grouped[j] = 1;
      scratch.group.push_back(outlines[j]);
      scratch.members.push_back(uint32_t(j));
    }
    if (scratch.group.size() >= 2 && coplanarOutlinesCover(s, r, scratch.group, eps)) return true;
  }
  return false;
}

}  // namespace gv
