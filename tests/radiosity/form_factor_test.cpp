// Form factors against closed forms from Howell's "A Catalog of Radiation Heat Transfer
// Configuration Factors" (configurations B-3, C-11, C-14), typed here from the catalogue.
#include "radiosity/form_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radiosity/element_tree.h"

namespace gv {
namespace {

const double kPi = std::numbers::pi;
const Tolerance kTol{10.0};

ConvexPolygon polygon(std::vector<Vec3> v) {
  return *ConvexPolygon::fromVertices(std::move(v), kTol);
}

/// Howell B-3: differential area to a parallel a × b rectangle, normal through one corner, at
/// distance c.
double howellPointToParallelRectangle(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * kPi);
}

/// Howell C-11: directly opposed parallel a × b rectangles at distance c.
double howellParallelRectangles(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double x2 = x * x, y2 = y * y;
  const double sx = std::sqrt(1 + x2), sy = std::sqrt(1 + y2);
  return 2 / (kPi * x * y) *
         (std::log(std::sqrt((1 + x2) * (1 + y2) / (1 + x2 + y2))) + x * sy * std::atan(x / sy) +
          y * sx * std::atan(y / sx) - x * std::atan(x) - y * std::atan(y));
}

/// Howell C-14: from rectangle 1 (width w, common edge l) to perpendicular rectangle 2 (height h,
/// the same common edge l).
double howellPerpendicularRectangles(double w, double h, double l) {
  const double W = w / l, H = h / l;
  const double W2 = W * W, H2 = H * H, s = std::sqrt(H2 + W2);
  const double t1 = (1 + W2) * (1 + H2) / (1 + W2 + H2);
  const double t2 = std::pow(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2)), W2);
  const double t3 = std::pow(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)), H2);
  return (W * std::atan(1 / W) + H * std::atan(1 / H) - s * std::atan(1 / s) +
          0.25 * std::log(t1 * t2 * t3)) /
         (kPi * W);
}

// Rectangle [0,a]x[0,b] at z = 0 facing +z, and one at z = c facing -z.
ConvexPolygon floorRect(double a, double b) {
  return polygon({{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}});
}
ConvexPolygon ceilingRect(double a, double b, double c) {
  return polygon({{0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c}});
}

TEST(FormFactorTest, PointToParallelRectangleMatchesHowellB3) {
  for (const auto& [a, b, c] :
       {std::array{1.0, 1.0, 1.0}, std::array{2.0, 0.5, 0.3}, std::array{0.1, 3.0, 2.0}}) {
    const ConvexPolygon r = ceilingRect(a, b, c);
    const double f = pointToPolygonFormFactor({0, 0, 0}, {0, 0, 1}, r.vertices);
    EXPECT_NEAR(f, howellPointToParallelRectangle(a, b, c), 1e-12) << a << " " << b << " " << c;
  }
}

TEST(FormFactorTest, ParallelOpposedRectanglesMatchHowellC11) {
  for (const auto& [a, b, c] : {std::array{1.0, 1.0, 1.0}, std::array{1.0, 1.0, 0.1},
                                std::array{2.0, 0.5, 0.25}, std::array{1.0, 1.0, 5.0}}) {
    const double expected = howellParallelRectangles(a, b, c);
    const double f = formFactor(floorRect(a, b), ceilingRect(a, b, c), kTol);
    EXPECT_NEAR(f, expected, 1e-3 * expected) << a << " " << b << " " << c;
  }
  // The catalogue's tabulated value for unit squares one unit apart.
  EXPECT_NEAR(howellParallelRectangles(1, 1, 1), 0.19982, 1e-5);
}

TEST(FormFactorTest, PerpendicularRectanglesSharingAnEdgeMatchHowellC14) {
  EXPECT_NEAR(howellPerpendicularRectangles(1, 1, 1), 0.20004, 1e-5);  // catalogue value
  for (const auto& [w, h, l] :
       {std::array{1.0, 1.0, 1.0}, std::array{2.0, 0.5, 1.0}, std::array{0.2, 3.0, 1.5}}) {
    // Rectangle 1 on the floor (x in [0,l], y in [0,w]) facing +z; rectangle 2 the wall y = 0
    // (x in [0,l], z in [0,h]) facing +y; common edge along x.
    const ConvexPolygon r1 = polygon({{0, 0, 0}, {l, 0, 0}, {l, w, 0}, {0, w, 0}});
    const ConvexPolygon r2 = polygon({{0, 0, 0}, {0, 0, h}, {l, 0, h}, {l, 0, 0}});
    const double expected = howellPerpendicularRectangles(w, h, l);
    EXPECT_NEAR(formFactor(r1, r2, kTol), expected, 1e-3 * expected) << w << " " << h << " " << l;
    // And the other way, by reciprocity of the closed form.
    const double back = expected * (w * l) / (h * l);
    EXPECT_NEAR(formFactor(r2, r1, kTol), back, 1e-3 * back);
  }
}

TEST(FormFactorTest, RefinedEstimateConvergesToHowell) {
  // The hierarchical solver sums child links: F(a → b) = Σ_children (A_c / A_a) F(c → b). The sum
  // over ever finer pieces of the receiver must stay on the catalogue value (contact case).
  const ConvexPolygon r1 = polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const ConvexPolygon r2 = polygon({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}});
  const double expected = howellPerpendicularRectangles(1, 1, 1);
  std::vector<ConvexPolygon> pieces{r1};
  for (int level = 0; level < 3; ++level) {
    std::vector<ConvexPolygon> next;
    for (const ConvexPolygon& p : pieces)
      for (ConvexPolygon& c : splitElementPolygon(p)) next.push_back(std::move(c));
    pieces = std::move(next);
    double sum = 0;
    for (const ConvexPolygon& p : pieces) sum += p.area() * formFactor(p, r2, kTol);
    EXPECT_NEAR(sum / r1.area(), expected, 1e-2 * expected) << "level " << level;
  }
}

TEST(FormFactorTest, ClosedCubeRowsSumToOne) {
  // Inward-facing unit cube: from any face, the other five faces fill the hemisphere.
  std::vector<ConvexPolygon> faces{
      polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}),  // z = 0 facing +z
      polygon({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}),  // z = 1 facing -z
      polygon({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}),  // x = 0 facing +x
      polygon({{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}}),  // x = 1 facing -x
      polygon({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}),  // y = 0 facing +y
      polygon({{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}),  // y = 1 facing -y
  };
  for (size_t i = 0; i < faces.size(); ++i) {
    double sum = 0;
    for (size_t j = 0; j < faces.size(); ++j)
      if (i != j) sum += formFactor(faces[i], faces[j], kTol);
    EXPECT_NEAR(sum, 1.0, 2e-4) << "face " << i;
  }
}

TEST(FormFactorTest, BackFacingAndCoplanarGiveZero) {
  const ConvexPolygon floor = floorRect(1, 1);
  // A rectangle above the floor facing up (away from it): cannot exchange light.
  const ConvexPolygon up = polygon({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}});
  EXPECT_FALSE(canFace(floor, up, 1e-9));
  EXPECT_EQ(formFactor(floor, up, kTol), 0.0);
  const ConvexPolygon beside = polygon({{2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0}});
  EXPECT_FALSE(canFace(floor, beside, 1e-9));
  EXPECT_EQ(formFactor(floor, beside, kTol), 0.0);
}

TEST(FormFactorTest, PartlyBehindIsClippedExactly) {
  // A wall x = 0 facing +x standing across the middle of a floor [-1,1]x[0,1]: only the floor's
  // x > 0 half sees the wall, i.e. F(floor → wall) is half of F(right half → wall).
  const ConvexPolygon floor = polygon({{-1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 1, 0}});
  const ConvexPolygon half = polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  const ConvexPolygon wall = polygon({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}});
  const double expected = howellPerpendicularRectangles(1, 1, 1);
  EXPECT_NEAR(formFactor(half, wall, kTol), expected, 1e-3 * expected);
  EXPECT_NEAR(formFactor(floor, wall, kTol), 0.5 * expected, 1e-3 * expected);
  // And the wall sees only the right half of the floor.
  EXPECT_NEAR(formFactor(wall, floor, kTol), expected, 1e-3 * expected);
}

TEST(FormFactorTest, ReciprocityOnSkewPolygons) {
  // A tilted triangle and a planar pentagon above it (z = 1.3 + 0.2 x + 0.1 y, clockwise seen
  // from above, so facing down), facing each other.
  const ConvexPolygon tri = polygon({{0, 0, 0}, {2, 0.3, 0}, {0.4, 1.5, 0.1}});
  auto above = [](double x, double y) { return Vec3{x, y, 1.3 + 0.2 * x + 0.1 * y}; };
  const ConvexPolygon pent = polygon(
      {above(0.2, 0.1), above(0.0, 1.0), above(1.0, 1.5), above(1.8, 0.8), above(1.2, 0.0)});
  ASSERT_TRUE(canFace(tri, pent, 1e-9));
  const double ab = formFactor(tri, pent, kTol) * tri.area();
  const double ba = formFactor(pent, tri, kTol) * pent.area();
  EXPECT_GT(ab, 0.0);
  EXPECT_NEAR(ab, ba, 1e-4 * ab);
}

}  // namespace
}  // namespace gv
