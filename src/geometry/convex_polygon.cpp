// Convex planar polygons: construction, measures, classification and splitting. Paper §3.
#include "geometry/convex_polygon.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gv {
namespace {

/// Twice the vector area of a closed polygon (Newell's method, written as a triangle fan around
/// the first vertex so that coordinates far from the origin do not cancel catastrophically).
Vec3 newellNormal(const std::vector<Vec3>& v) {
  Vec3 n{};
  const Vec3 o = v[0];
  for (std::size_t i = 1; i + 1 < v.size(); ++i) n += cross(v[i] - o, v[i + 1] - o);
  return n;
}

/// Removes consecutive vertices closer than eps (including last-to-first) and then vertices lying
/// within eps of the line through their neighbours (collinear middles and back-tracking spikes).
/// Repeats the second pass until stable because removing one vertex changes its neighbours' test.
void cleanVertices(std::vector<Vec3>& v, double eps) {
  // In place: this runs on every split piece, so avoid a second allocation.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (kept == 0 || distance(v[kept - 1], v[i]) > eps) v[kept++] = v[i];
  }
  while (kept > 1 && distance(v[kept - 1], v[0]) <= eps) --kept;
  v.resize(kept);

  bool changed = true;
  while (changed && v.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < v.size() && v.size() >= 3; ++i) {
      const Vec3& prev = v[(i + v.size() - 1) % v.size()];
      const Vec3& next = v[(i + 1) % v.size()];
      const Vec3 chord = next - prev;
      const double chordLength = length(chord);
      // Distance of v[i] from the line prev-next; a vanishing chord means a spike out and back.
      const bool collinear =
          chordLength <= eps || length(cross(chord, v[i] - prev)) <= eps * chordLength;
      if (collinear) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        --i;  // re-test the vertex that moved into slot i (wraps harmlessly at i == 0)
      }
    }
  }
}

double longestEdge(const std::vector<Vec3>& v) {
  double longest = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    longest = std::max(longest, distance(v[i], v[(i + 1) % v.size()]));
  }
  return longest;
}

/// True when a polygon of this (positive) area and these vertices is at least eps wide.
bool wideEnough(double area, const std::vector<Vec3>& v, double eps) {
  const double longest = longestEdge(v);
  return longest > 0 && 2.0 * area / longest >= eps;
}

}  // namespace

std::optional<ConvexPolygon> ConvexPolygon::fromVertices(std::vector<Vec3> vertices,
                                                         const Tolerance& tol) {
  const double eps = tol.length();
  cleanVertices(vertices, eps);
  if (vertices.size() < 3) return std::nullopt;
  const Vec3 n2 = newellNormal(vertices);
  const double area = 0.5 * length(n2);
  if (!(area > 0) || !wideEnough(area, vertices, eps)) return std::nullopt;
  const Vec3 normal = n2 / (2.0 * area);
  // Offset from the mean of all vertices: the least-squares plane for this normal.
  double offset = 0;
  for (const Vec3& p : vertices) offset += dot(normal, p);
  offset /= static_cast<double>(vertices.size());
  return ConvexPolygon{std::move(vertices), Plane{normal, offset}};
}

std::optional<ConvexPolygon> ConvexPolygon::fromVerticesInPlane(std::vector<Vec3> vertices,
                                                                const Plane& plane,
                                                                const Tolerance& tol) {
  const double eps = tol.length();
  cleanVertices(vertices, eps);
  if (vertices.size() < 3) return std::nullopt;
  // Signed against the given plane: clockwise input (negative area) is degenerate here.
  const double area = 0.5 * dot(newellNormal(vertices), plane.normal);
  if (!(area > 0) || !wideEnough(area, vertices, eps)) return std::nullopt;
  return ConvexPolygon{std::move(vertices), plane};
}

double ConvexPolygon::area() const {
  return 0.5 * dot(newellNormal(vertices), plane.normal);
}

Vec3 ConvexPolygon::centroid() const {
  const Vec3 o = vertices[0];
  Vec3 weighted{};
  double total = 0;
  for (std::size_t i = 1; i + 1 < vertices.size(); ++i) {
    const double w = dot(cross(vertices[i] - o, vertices[i + 1] - o), plane.normal);
    weighted += (vertices[i] + vertices[i + 1] - 2.0 * o) * (w / 3.0);
    total += w;
  }
  return total > 0 ? o + weighted / total : o;
}

Aabb ConvexPolygon::bounds() const {
  Aabb box;
  for (const Vec3& p : vertices) box.add(p);
  return box;
}

ConvexPolygon ConvexPolygon::flipped() const {
  ConvexPolygon out{vertices, plane.flipped()};
  std::reverse(out.vertices.begin(), out.vertices.end());
  return out;
}

PlaneSide ConvexPolygon::classify(const Plane& splitter, const Tolerance& tol) const {
  const double eps = tol.length();
  bool front = false, back = false;
  for (const Vec3& p : vertices) {
    const PlaneSide s = splitter.side(p, eps);
    front |= s == PlaneSide::Front;
    back |= s == PlaneSide::Back;
  }
  if (front && back) return PlaneSide::Spanning;
  if (front) return PlaneSide::Front;
  if (back) return PlaneSide::Back;
  return PlaneSide::On;
}

bool ConvexPolygon::contains(const Vec3& p, const Tolerance& tol) const {
  const double eps = tol.length();
  if (std::abs(plane.distance(p)) > eps) return false;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Vec3& a = vertices[i];
    const Vec3 edge = vertices[(i + 1) % vertices.size()] - a;
    // cross(normal, edge) points into a counter-clockwise polygon; compare distances, not raw
    // products, so the tolerance keeps its meaning of a length.
    if (dot(cross(plane.normal, edge), p - a) < -eps * length(edge)) return false;
  }
  return true;
}

Vec3 ConvexPolygon::nearestPoint(const Vec3& x) const {
  const Vec3 onPlane = x - plane.distance(x) * plane.normal;
  bool inside = true;
  Vec3 best = vertices[0];
  double bestDistance = INFINITY;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Vec3& a = vertices[i];
    const Vec3& b = vertices[(i + 1) % vertices.size()];
    const Vec3 edge = b - a;
    if (dot(cross(edge, onPlane - a), plane.normal) < 0) inside = false;
    const double len2 = dot(edge, edge);
    const double t = len2 > 0 ? std::clamp(dot(onPlane - a, edge) / len2, 0.0, 1.0) : 0.0;
    const Vec3 q = a + t * edge;
    if (distance(q, onPlane) < bestDistance) {
      bestDistance = distance(q, onPlane);
      best = q;
    }
  }
  return inside ? onPlane : best;
}

PolygonSplit split(const ConvexPolygon& polygon, const Plane& splitter, const Tolerance& tol) {
  const double eps = tol.length();
  const std::size_t n = polygon.vertices.size();
  std::vector<double> dist(n);
  auto sideOf = [&](std::size_t i) {
    return dist[i] > eps ? PlaneSide::Front : (dist[i] < -eps ? PlaneSide::Back : PlaneSide::On);
  };
  bool anyFront = false, anyBack = false;
  for (std::size_t i = 0; i < n; ++i) {
    dist[i] = splitter.distance(polygon.vertices[i]);
    anyFront |= dist[i] > eps;
    anyBack |= dist[i] < -eps;
  }
  PolygonSplit out;
  if (!anyFront && !anyBack) {
    out.on = polygon;
    return out;
  }
  if (!anyBack) {
    out.front = polygon;
    return out;
  }
  if (!anyFront) {
    out.back = polygon;
    return out;
  }

  std::vector<Vec3> front, back;
  front.reserve(n + 2);
  back.reserve(n + 2);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const Vec3& p = polygon.vertices[i];
    const PlaneSide si = sideOf(i), sj = sideOf(j);
    if (si != PlaneSide::Back) front.push_back(p);
    if (si != PlaneSide::Front) back.push_back(p);
    const bool crosses = (si == PlaneSide::Front && sj == PlaneSide::Back) ||
                         (si == PlaneSide::Back && sj == PlaneSide::Front);
    if (!crosses) continue;
    // Interpolate always from the front end point so that the two faces sharing this edge (which
    // walk it in opposite directions) compute bit-identical crossing points.
    const std::size_t f = si == PlaneSide::Front ? i : j;
    const std::size_t b = f == i ? j : i;
    const double t = dist[f] / (dist[f] - dist[b]);
    const Vec3 x = polygon.vertices[f] + (polygon.vertices[b] - polygon.vertices[f]) * t;
    front.push_back(x);
    back.push_back(x);
  }
  out.front = ConvexPolygon::fromVerticesInPlane(std::move(front), polygon.plane, tol);
  out.back = ConvexPolygon::fromVerticesInPlane(std::move(back), polygon.plane, tol);
  return out;
}

std::optional<ConvexPolygon> clipToFront(const ConvexPolygon& polygon, const Plane& plane,
                                         const Tolerance& tol) {
  PolygonSplit pieces = split(polygon, plane, tol);
  if (pieces.on) return std::move(pieces.on);
  return std::move(pieces.front);
}

bool canFace(const ConvexPolygon& a, const ConvexPolygon& b, double eps) {
  auto someInFront = [eps](const ConvexPolygon& of, const ConvexPolygon& plane) {
    for (const Vec3& v : of.vertices)
      if (plane.plane.distance(v) > eps) return true;
    return false;
  };
  return someInFront(b, a) && someInFront(a, b);
}

}  // namespace gv
