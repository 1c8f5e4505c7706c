// Convex polyhedra: construction from boxes and halfspaces, measures, and robust splitting into
// the two child cells of a BSP node. Paper §3.
#include "geometry/convex_polyhedron.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gv {
namespace {

/// A square of half-size `halfSize` on `plane`, centred at the point of the plane nearest to
/// `near`, counter-clockwise seen from the plane's front.
ConvexPolygon squareOn(const Plane& plane, const Vec3& near, double halfSize) {
  const Vec3& n = plane.normal;
  // (u, v, n) right-handed, so u→v turns counter-clockwise about n.
  const auto [u, v] = perpendicularFrame(n);
  const Vec3 c = near - n * plane.distance(near);
  const Vec3 du = u * halfSize, dv = v * halfSize;
  return ConvexPolygon{{c - du - dv, c + du - dv, c + du + dv, c - du + dv}, plane};
}

/// The part of `polygon` inside every halfspace except `skip` (-1: none); nullopt when nothing
/// (or only a sliver) is left.
std::optional<ConvexPolygon> clipToHalfspaces(ConvexPolygon polygon,
                                              const std::vector<Plane>& halfspaces, int skip,
                                              const Tolerance& tol) {
  for (std::size_t j = 0; j < halfspaces.size(); ++j) {
    if (static_cast<int>(j) == skip) continue;
    // Inside is distance <= 0: keep what is in front of the flipped plane (or on it).
    std::optional<ConvexPolygon> clipped = clipToFront(polygon, halfspaces[j].flipped(), tol);
    if (!clipped) return std::nullopt;
    polygon = std::move(*clipped);
  }
  return polygon;
}

/// Keeps only the halfspaces that support a face and renumbers the faces' references to match.
void compactHalfspaces(ConvexPolyhedron& p) {
  std::vector<int> newIndex(p.halfspaces.size(), -1);
  std::vector<Plane> kept;
  for (PolyhedronFace& f : p.faces) {
    int& slot = newIndex[static_cast<std::size_t>(f.halfspace)];
    if (slot < 0) {
      slot = static_cast<int>(kept.size());
      kept.push_back(p.halfspaces[static_cast<std::size_t>(f.halfspace)]);
    }
    f.halfspace = slot;
  }
  p.halfspaces = std::move(kept);
}

/// True when, for every face, some vertex lies at least eps behind the face's plane: the solid
/// is not a flat sheet (which, for a convex body, is what "thinner than eps" means face by face).
bool thickEnough(const ConvexPolyhedron& p, double eps) {
  for (const PolyhedronFace& f : p.faces) {
    double deepest = 0;
    for (const PolyhedronFace& g : p.faces) {
      for (const Vec3& v : g.polygon.vertices) {
        deepest = std::max(deepest, -f.polygon.plane.distance(v));
      }
    }
    if (deepest < eps) return false;
  }
  return true;
}

/// Smallest and largest signed distance of the polyhedron's vertices from `plane`.
std::pair<double, double> distanceRange(const ConvexPolyhedron& p, const Plane& plane) {
  double lo = INFINITY, hi = -INFINITY;
  for (const PolyhedronFace& f : p.faces) {
    for (const Vec3& v : f.polygon.vertices) {
      const double d = plane.distance(v);
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  }
  return {lo, hi};
}

}  // namespace

std::optional<ConvexPolyhedron> ConvexPolyhedron::fromAabb(const Aabb& box) {
  if (box.empty()) return std::nullopt;
  const Vec3 e = box.extent();
  if (!(e.x > 0 && e.y > 0 && e.z > 0)) return std::nullopt;
  ConvexPolyhedron p;
  for (int axis = 0; axis < 3; ++axis) {
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;  // e_a1 x e_a2 = e_axis
    for (int s = -1; s <= 1; s += 2) {
      Vec3 n{};
      n[axis] = s;
      const double coord = s < 0 ? box.lo[axis] : box.hi[axis];
      const Plane plane{n, s * coord};
      auto corner = [&](bool hi1, bool hi2) {
        Vec3 c{};
        c[axis] = coord;
        c[a1] = hi1 ? box.hi[a1] : box.lo[a1];
        c[a2] = hi2 ? box.hi[a2] : box.lo[a2];
        return c;
      };
      // Counter-clockwise about +e_axis; reversed for the face looking down -e_axis.
      std::vector<Vec3> v{corner(false, false), corner(true, false), corner(true, true),
                          corner(false, true)};
      if (s < 0) std::reverse(v.begin(), v.end());
      p.faces.push_back(
          {ConvexPolygon{std::move(v), plane}, static_cast<int>(p.halfspaces.size())});
      p.halfspaces.push_back(plane);
    }
  }
  return p;
}

std::optional<ConvexPolyhedron> ConvexPolyhedron::fromHalfspaces(const std::vector<Plane>& planes,
                                                                 const Tolerance& tol) {
  const double eps = tol.length();
  // Merge duplicates first: two copies of one plane would each claim the same face.
  std::vector<Plane> unique;
  for (const Plane& h : planes) {
    const bool duplicate = std::any_of(unique.begin(), unique.end(), [&](const Plane& k) {
      return dot(k.normal, h.normal) >= 1 - tol.normalCos() && std::abs(k.offset - h.offset) <= eps;
    });
    if (!duplicate) unique.push_back(h);
  }
  double maxOffset = 0;
  for (const Plane& h : unique) maxOffset = std::max(maxOffset, std::abs(h.offset));
  const double reach = kHalfspaceReachFactor * (tol.scale + maxOffset);

  // Faces are squares on each plane clipped by all the other halfspaces.
  auto buildFaces = [&](const Vec3& near, double halfSize) {
    ConvexPolyhedron p;
    p.halfspaces = unique;
    for (std::size_t i = 0; i < unique.size(); ++i) {
      std::optional<ConvexPolygon> face =
          clipToHalfspaces(squareOn(unique[i], near, halfSize), unique, static_cast<int>(i), tol);
      if (face) p.faces.push_back({std::move(*face), static_cast<int>(i)});
    }
    return p;
  };
  ConvexPolyhedron p = buildFaces(Vec3{}, reach);
  if (p.faces.size() < 4) return std::nullopt;
  // A face still reaching the initial square's border means the intersection is unbounded (the
  // square's centre is within reach/1000 of the origin, its border at least ~reach away).
  for (const PolyhedronFace& f : p.faces) {
    for (const Vec3& v : f.polygon.vertices) {
      if (length(v) > 0.5 * reach) return std::nullopt;
    }
  }
  // Rebuild with squares just larger than the solid: clipping the huge first squares rounds at
  // the scale of `reach`, these round at the scale of the solid itself.
  const Aabb box = p.bounds();
  p = buildFaces(box.center(), box.diagonal());
  if (p.faces.size() < 4) return std::nullopt;
  compactHalfspaces(p);
  if (!thickEnough(p, eps)) return std::nullopt;
  return p;
}

double ConvexPolyhedron::volume() const {
  // Sum of signed tetrahedra (ref, fan triangle) over the outward faces; ref is a vertex so that
  // the terms stay small when the cell is far from the origin.
  const Vec3 ref = faces.front().polygon.vertices.front();
  double sixV = 0;
  for (const PolyhedronFace& f : faces) {
    const std::vector<Vec3>& v = f.polygon.vertices;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
      sixV += dot(cross(v[i] - v[0], v[i + 1] - v[0]), v[0] - ref);
    }
  }
  return sixV / 6.0;
}

Vec3 ConvexPolyhedron::centroid() const {
  const Vec3 ref = faces.front().polygon.vertices.front();
  Vec3 weighted{};
  double total = 0;
  for (const PolyhedronFace& f : faces) {
    const std::vector<Vec3>& v = f.polygon.vertices;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
      const Vec3 a = v[0] - ref, b = v[i] - ref, c = v[i + 1] - ref;
      const double w = dot(cross(b - a, c - a), a);  // six times the tetra (ref, a, b, c) volume
      weighted += (a + b + c) * (w / 4.0);
      total += w;
    }
  }
  return total > 0 ? ref + weighted / total : ref;
}

Aabb ConvexPolyhedron::bounds() const {
  Aabb box;
  for (const PolyhedronFace& f : faces) box.add(f.polygon.bounds());
  return box;
}

bool ConvexPolyhedron::contains(const Vec3& p, const Tolerance& tol) const {
  const double eps = tol.length();
  return std::all_of(halfspaces.begin(), halfspaces.end(),
                     [&](const Plane& h) { return h.distance(p) <= eps; });
}

PlaneSide ConvexPolyhedron::classify(const Plane& plane, const Tolerance& tol) const {
  const double eps = tol.length();
  const auto [lo, hi] = distanceRange(*this, plane);
  if (lo < -eps && hi > eps) return PlaneSide::Spanning;
  if (hi > eps) return PlaneSide::Front;
  if (lo < -eps) return PlaneSide::Back;
  return PlaneSide::On;
}

PolyhedronSplit split(const ConvexPolyhedron& polyhedron, const Plane& splitter,
                      const Tolerance& tol, int capPlaneId) {
  PolyhedronSplit out;
  // Plain variables, not a structured binding: clang 14 cannot capture bindings in lambdas.
  const auto range = distanceRange(polyhedron, splitter);
  const double lo = range.first, hi = range.second;
  // The whole cell goes to the side it reaches further into when the cut is not a real one.
  auto whole = [&] {
    if (hi >= -lo) {
      out.front = polyhedron;
    } else {
      out.back = polyhedron;
    }
    return out;
  };
  switch (polyhedron.classify(splitter, tol)) {
    case PlaneSide::Front:
      out.front = polyhedron;
      return out;
    case PlaneSide::Back:
      out.back = polyhedron;
      return out;
    case PlaneSide::On:
      return whole();
    case PlaneSide::Spanning:
      break;
  }

  // The cap: the splitting plane's section of the cell, found the same way as the faces of
  // fromHalfspaces (a square larger than the cell, clipped by every halfspace).
  const Aabb box = polyhedron.bounds();
  const std::optional<ConvexPolygon> cap = clipToHalfspaces(
      squareOn(splitter, box.center(), box.diagonal()), polyhedron.halfspaces, -1, tol);
  if (!cap) return whole();  // the section is a sliver: the cut grazes the cell

  ConvexPolyhedron front, back;
  front.halfspaces = back.halfspaces = polyhedron.halfspaces;
  for (const PolyhedronFace& f : polyhedron.faces) {
    PolygonSplit pieces = split(f.polygon, splitter, tol);
    if (pieces.front) front.faces.push_back({std::move(*pieces.front), f.halfspace, f.planeId});
    if (pieces.back) back.faces.push_back({std::move(*pieces.back), f.halfspace, f.planeId});
    // A face on the splitter cannot occur in a spanning cell; if rounding makes one, the cap
    // replaces it.
  }
  const int capIndex = static_cast<int>(polyhedron.halfspaces.size());
  back.halfspaces.push_back(splitter);
  back.faces.push_back({*cap, capIndex, capPlaneId});
  front.halfspaces.push_back(splitter.flipped());
  front.faces.push_back({cap->flipped(), capIndex, capPlaneId});

  const double eps = tol.length();
  for (auto [piece, slot] : {std::pair{&front, &out.front}, std::pair{&back, &out.back}}) {
    if (piece->faces.size() < 4) continue;
    compactHalfspaces(*piece);
    if (thickEnough(*piece, eps)) *slot = std::move(*piece);
  }
  if (!out.front && !out.back) return whole();
  return out;
}

}  // namespace gv
