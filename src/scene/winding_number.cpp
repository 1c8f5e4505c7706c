#include "scene/winding_number.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/fast_atan2.h"

namespace gv {
namespace {

/// Triangles per leaf of the hierarchy.
constexpr uint32_t kLeafTriangles = 8;

/// Signed solid angle of triangle (a, b, c) seen from the origin (Van Oosterom & Strackee 1983):
/// positive when a · (b × c) > 0, i.e. the triangle runs clockwise seen from the origin.
double solidAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = length(a), lb = length(b), lc = length(c);
  const double det = dot(a, cross(b, c));
  const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2 * fastAtan2(det, den);
}

}  // namespace

double windingNumber(const Scene& scene, const Vec3& p) {
  double sum = 0;
  for (const Patch& patch : scene.patches) {
    const auto& v = patch.polygon.vertices;
    const Vec3 a = v[0] - p;
    for (size_t i = 1; i + 1 < v.size(); ++i) sum += solidAngle(a, v[i] - p, v[i + 1] - p);
  }
  // Counter-clockwise seen from the front = outward: from a point inside, each face's triangle
  // (vertices minus p) has a positive triple product, and a closed solid adds up to 4 pi.
  return sum / (4 * std::numbers::pi);
}

WindingNumberField::WindingNumberField(const Scene& scene) {
  for (const Patch& patch : scene.patches) {
    const auto& v = patch.polygon.vertices;
    for (size_t i = 1; i + 1 < v.size(); ++i) triangles_.push_back({v[0], v[i], v[i + 1]});
  }
  if (!triangles_.empty()) build(0, uint32_t(triangles_.size()));
}

int32_t WindingNumberField::build(uint32_t first, uint32_t count) {
  Node node;
  Aabb box;
  double areaSum = 0;
  Vec3 weighted{};
  for (uint32_t t = first; t < first + count; ++t) {
    const Triangle& tr = triangles_[t];
    const Vec3 area = cross(tr.b - tr.a, tr.c - tr.a) * 0.5;
    const double a = length(area);
    node.areaVector = node.areaVector + area;
    weighted = weighted + (tr.a + tr.b + tr.c) * (a / 3);
    areaSum += a;
    box.add(tr.a);
    box.add(tr.b);
    box.add(tr.c);
  }
  node.centre = areaSum > 0 ? weighted / areaSum : box.center();
  for (uint32_t t = first; t < first + count; ++t)
    for (const Vec3& v : {triangles_[t].a, triangles_[t].b, triangles_[t].c})
      node.radius = std::max(node.radius, length(v - node.centre));
  const auto id = static_cast<int32_t>(nodes_.size());
  nodes_.push_back(node);
  if (count <= kLeafTriangles) {
    nodes_[size_t(id)].first = first;
    nodes_[size_t(id)].count = count;
    return id;
  }
  // Median split along the box's longest axis, by triangle centroid.
  const Vec3 ext = box.extent();
  const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
  const uint32_t half = count / 2;
  std::nth_element(
      triangles_.begin() + first, triangles_.begin() + first + half,
      triangles_.begin() + first + count, [axis](const Triangle& l, const Triangle& r) {
        return (l.a[axis] + l.b[axis] + l.c[axis]) < (r.a[axis] + r.b[axis] + r.c[axis]);
      });
  const int32_t left = build(first, half);
  const int32_t right = build(first + half, count - half);
  nodes_[size_t(id)].left = left;
  nodes_[size_t(id)].right = right;
  return id;
}

double WindingNumberField::at(const Vec3& p) const {
  if (nodes_.empty()) return 0;
  double sum = 0;      // in steradians
  int32_t stack[128];  // a median split is at most ~log2(triangles) deep: far below this
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[size_t(stack[--top])];
    const Vec3 d = node.centre - p;
    const double dist = length(d);
    if (dist > kWindingFarRatio * node.radius) {
      // The cluster as one dipole: its area vector seen from p.
      sum += dot(node.areaVector, d) / (dist * dist * dist);
      continue;
    }
    if (node.left < 0) {
      for (uint32_t t = node.first; t < node.first + node.count; ++t) {
        const Triangle& tr = triangles_[t];
        sum += solidAngle(tr.a - p, tr.b - p, tr.c - p);
      }
      continue;
    }
    stack[top++] = node.left;
    stack[top++] = node.right;
  }
  return sum / (4 * std::numbers::pi);
}

}  // namespace gv
