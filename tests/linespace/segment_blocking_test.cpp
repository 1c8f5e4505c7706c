// The segment/blocker test of the linespace (paper §6.3) on a blocker a hair out of true: a
// real level's bevel whose corner was imported twice.
#include "linespace/segment_blocking.h"

#include <gtest/gtest.h>

#include "geometry/convex_polygon.h"

namespace gv {
namespace {

TEST(SegmentBlocking, ABlockerWithACornerTwinnedOffItsPlaneStopsSegmentsThroughItsMiddle) {
  // q3-oacmpdm3's patch 3130: a 45° bevel (normal (-1, 0, 1) / sqrt 2) whose corner at
  // (42, 36, 16.125) the OBJ holds twice, 1e-6 apart along x. The edge between the copies
  // leaves the bevel's plane at 45°.
  const Tolerance tol{118.028};
  const auto bevel = ConvexPolygon::fromVertices({{42.000001, 36, 16.125},
                                                  {42, 36, 16.125},
                                                  {42, 34, 16.125},
                                                  {42.125, 34.125001, 16.25},
                                                  {42.125, 35.875, 16.25}},
                                                 tol);
  ASSERT_TRUE(bevel);
  ASSERT_EQ(bevel->vertices.size(), 5u);  // the twin is kept: 1e-6 is above the length tolerance
  const BlockerTable table(std::span<const ConvexPolygon>(&*bevel, 1));
  const uint32_t only[] = {0};
  // Segments through points well inside the bevel (0.03-0.06 from its edges, on its plane
  // x - z = 25.875), going the way of the sightline `vis` missed (down and towards -x) and the
  // opposite way, from 1 unit in front to 1 unit behind.
  const Vec3 directions[] = {normalize(Vec3{-24, -4.5, -9.7}), normalize(Vec3{24, 4.5, 9.7}),
                             normalize(Vec3{-1, 0, 1}), normalize(Vec3{-1, 1, 0.3})};
  const Vec3 inside[] = {{42.03, 34.09, 16.155}, {42.0625, 35, 16.1875}, {42.1, 35.8, 16.225}};
  for (const Vec3& x : inside) {
    ASSERT_NEAR(x.x - x.z, 25.875, 1e-12);
    for (const Vec3& d : directions) {
      const Vec3 p = x - d, q = x + d;
      EXPECT_TRUE(segmentBlocked(p, q, only, table, tol.length()))
          << "through (" << x.x << ", " << x.y << ", " << x.z << ") along (" << d.x << ", " << d.y
          << ", " << d.z << ")";
    }
  }
  // And segments passing 0.05 beside it are not stopped.
  EXPECT_FALSE(segmentBlocked({41.95, 33.95, 17}, {42.0, 33.95, 15}, only, table, tol.length()));
}

}  // namespace
}  // namespace gv
