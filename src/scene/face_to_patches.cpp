// Face → convex patches: dedupe, planarity test, convex partition (CGAL Partition_2) or
// triangulation. Keeps the input vertices; only decides how to group them.
#include "scene/face_to_patches.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Partition_traits_2.h>
#include <CGAL/partition_2.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <list>

namespace gv {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using IndexTraits = CGAL::Partition_traits_2<Kernel, CGAL::Pointer_property_map<Point2>::type>;
using IndexPolygon = IndexTraits::Polygon_2;

/// Newell's normal: twice the vector area; robust for non-planar and non-convex loops.
Vec3 newellNormal(const std::vector<Vec3>& v) {
  Vec3 n;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3& a = v[i];
    const Vec3& b = v[(i + 1) % v.size()];
    n += cross(a, b);
  }
  return n;
}

std::vector<Vec3> dropRepeatedVertices(const std::vector<Vec3>& face, double eps) {
  std::vector<Vec3> out;
  for (const Vec3& p : face)
    if (out.empty() || distance(out.back(), p) > eps) out.push_back(p);
  while (out.size() > 1 && distance(out.front(), out.back()) <= eps) out.pop_back();
  return out;
}

/// 2D projection dropping the normal's dominant axis, mirrored when needed so that the face's
/// front-side counter-clockwise order stays counter-clockwise in 2D.
std::vector<Point2> project(const std::vector<Vec3>& v, const Vec3& normal) {
  const int drop = dominantAxis(normal);
  const int u = (drop + 1) % 3, w = (drop + 2) % 3;
  const bool mirror = normal[drop] < 0;
  std::vector<Point2> out;
  out.reserve(v.size());
  for (const Vec3& p : v) out.emplace_back(mirror ? p[w] : p[u], mirror ? p[u] : p[w]);
  return out;
}

bool isConvexCcw(const std::vector<Point2>& p) {
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i)
    if (CGAL::orientation(p[i], p[(i + 1) % n], p[(i + 2) % n]) == CGAL::RIGHT_TURN) return false;
  return true;
}

/// Adds the piece if it is a usable polygon facing the same way as the face. A piece of a split
/// face is held to the face's own sliver rule (unless `keepSlivers`, for files this tool wrote): a
/// user's face that thin is dropped, and so is a piece of one.
void addPiece(std::vector<Vec3> verts, const Vec3& faceNormal, const Tolerance& tol,
              bool keepSlivers, std::vector<ConvexPolygon>& out) {
  auto poly = ConvexPolygon::fromVertices(std::move(verts), tol);
  if (!poly || dot(poly->plane.normal, faceNormal) <= 0 || (!keepSlivers && isSliver(*poly, tol)))
    return;
  out.push_back(std::move(*poly));
}

void addFan(const std::vector<Vec3>& v, const std::vector<size_t>& idx, const Vec3& faceNormal,
            const Tolerance& tol, bool keepSlivers, std::vector<ConvexPolygon>& out) {
  for (size_t i = 1; i + 1 < idx.size(); ++i)
    addPiece({v[idx[0]], v[idx[i]], v[idx[i + 1]]}, faceNormal, tol, keepSlivers, out);
}

}  // namespace

double diameterOf(const std::vector<Vec3>& vertices) {
  double d = 0;
  for (size_t i = 0; i < vertices.size(); ++i)
    for (size_t j = i + 1; j < vertices.size(); ++j)
      d = std::max(d, distance(vertices[i], vertices[j]));
  return d;
}

bool isSliver(double twiceArea, double diameter, const Tolerance& tol) {
  return twiceArea / std::max(diameter, tol.length()) <= tol.planeOffset();
}

FacePatches faceToPatches(const std::vector<Vec3>& face, const Tolerance& tol, bool keepSlivers) {
  FacePatches result;
  for (const Vec3& p : face)
    if (!isFinite(p)) return result;  // importers reject these earlier; stay safe anyway
  const std::vector<Vec3> v = dropRepeatedVertices(face, tol.length());
  if (v.size() < 3) return result;
  const Vec3 n2 = newellNormal(v);
  const double diameter = diameterOf(v);
  // Zero area (or a bow tie whose halves cancel) has no normal to face by, slivers or not.
  if (!(length(n2) > 0) || (!keepSlivers && isSliver(length(n2), diameter, tol))) return result;
  const Vec3 normal = normalize(n2);

  Vec3 centroid;
  for (const Vec3& p : v) centroid += p;
  centroid = centroid / static_cast<double>(v.size());
  double maxOff = 0;
  for (const Vec3& p : v) maxOff = std::max(maxOff, std::abs(dot(p - centroid, normal)));
  const bool planar = maxOff <= kRelativeModelEpsilon * diameter + tol.length();

  std::vector<Point2> pts = project(v, normal);
  std::vector<size_t> all(v.size());
  for (size_t i = 0; i < v.size(); ++i) all[i] = i;

  if (isConvexCcw(pts)) {
    if (planar) {
      addPiece(v, normal, tol, keepSlivers, result.pieces);
      result.outcome = FaceOutcome::Convex;
    } else {
      addFan(v, all, normal, tol, keepSlivers, result.pieces);
      result.outcome = FaceOutcome::Triangulated;
    }
  } else {
    IndexTraits traits(CGAL::make_property_map(pts));
    IndexPolygon polygon(traits);
    for (size_t i = 0; i < pts.size(); ++i) polygon.push_back(i);
    if (polygon.is_simple() && polygon.orientation() == CGAL::COUNTERCLOCKWISE) {
      std::list<IndexPolygon> parts;
      CGAL::approx_convex_partition_2(polygon.vertices_begin(), polygon.vertices_end(),
                                      std::back_inserter(parts), traits);
      for (const IndexPolygon& part : parts) {
        std::vector<size_t> idx(part.vertices_begin(), part.vertices_end());
        if (planar) {
          std::vector<Vec3> piece;
          for (size_t i : idx) piece.push_back(v[i]);
          addPiece(std::move(piece), normal, tol, keepSlivers, result.pieces);
        } else {
          addFan(v, idx, normal, tol, keepSlivers, result.pieces);
        }
      }
      result.outcome = planar ? FaceOutcome::SplitConvex : FaceOutcome::Triangulated;
    } else {
      // Self-intersecting (or clockwise-dominated) loop: no partition is meaningful. Fan it and
      // keep the triangles that face the way the face does; they cover what can be salvaged.
      addFan(v, all, normal, tol, keepSlivers, result.pieces);
      result.outcome = FaceOutcome::Triangulated;
    }
  }
  if (result.pieces.empty()) result.outcome = FaceOutcome::Degenerate;
  return result;
}

bool countFaceOutcome(FaceOutcome outcome, ImportReport& report) {
  switch (outcome) {
    case FaceOutcome::Degenerate:
      ++report.droppedDegenerate;
      return false;
    case FaceOutcome::SplitConvex:
      ++report.splitNonConvex;
      break;
    case FaceOutcome::Triangulated:
      ++report.triangulatedNonPlanar;
      break;
    case FaceOutcome::Convex:
      break;
  }
  return true;
}

}  // namespace gv
