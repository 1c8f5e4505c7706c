// 3D vectors in double precision: the coordinate type of the whole pipeline.
#pragma once

#include <cmath>
#include <ostream>

namespace gv {

/// A point or direction in world space. Plain data; all operations are inline.
struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}

  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  constexpr bool operator==(const Vec3& o) const = default;
};

constexpr Vec3 operator*(double s, const Vec3& v) {
  return v * s;
}
constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr double lengthSquared(const Vec3& v) {
  return dot(v, v);
}
inline double length(const Vec3& v) {
  return std::sqrt(dot(v, v));
}
inline double distance(const Vec3& a, const Vec3& b) {
  return length(a - b);
}
/// Unit vector along v; v must not be zero (callers check degeneracy first).
inline Vec3 normalize(const Vec3& v) {
  return v / length(v);
}
constexpr Vec3 min(const Vec3& a, const Vec3& b) {
  return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
constexpr Vec3 max(const Vec3& a, const Vec3& b) {
  return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
inline bool isFinite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
/// Index (0, 1, 2) of the coordinate with the largest magnitude: the axis to drop when
/// projecting a polygon with this normal to 2D without degeneracy.
inline int dominantAxis(const Vec3& v) {
  const double ax = std::abs(v.x), ay = std::abs(v.y), az = std::abs(v.z);
  return ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
}

/// Two unit vectors perpendicular to the unit vector `n` and to each other, (u, v, n)
/// right-handed: u = normalize(n × e) with e the x axis unless n is near it (then y).
struct PerpendicularFrame {
  Vec3 u, v;
};
inline PerpendicularFrame perpendicularFrame(const Vec3& n) {
  const Vec3 u = normalize(cross(n, std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  return {u, cross(n, u)};
}

inline std::ostream& operator<<(std::ostream& os, const Vec3& v) {
  return os << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}

/// Axis-aligned bounding box; empty until a point is added.
struct Aabb {
  Vec3 lo{INFINITY, INFINITY, INFINITY};
  Vec3 hi{-INFINITY, -INFINITY, -INFINITY};

  void add(const Vec3& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void add(const Aabb& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x; }
  /// This box grown by `slack` on every side meets `o` (touching counts).
  bool meets(const Aabb& o, double slack) const {
    return lo.x <= o.hi.x + slack && o.lo.x <= hi.x + slack && lo.y <= o.hi.y + slack &&
           o.lo.y <= hi.y + slack && lo.z <= o.hi.z + slack && o.lo.z <= hi.z + slack;
  }
  /// This box grown by `slack` on every side (an empty box stays empty).
  Aabb grown(double slack) const {
    return empty() ? *this : Aabb{lo - Vec3{slack, slack, slack}, hi + Vec3{slack, slack, slack}};
  }
  Vec3 extent() const { return empty() ? Vec3{} : hi - lo; }
  Vec3 center() const { return (lo + hi) * 0.5; }
  double diagonal() const { return empty() ? 0.0 : length(hi - lo); }
};

}  // namespace gv
