// The cell graph written as a Quake portal file (bsp/subdivision_io.h: writePortalsPrt): read back
// by the project's own .prt reader it is the same graph, oriented as qbsp orients its portals.
// (That `globalvis pvs` runs on what `globalvis cells` writes: subdivision_cli_test.cpp.)
#include <gtest/gtest.h>

#include "bsp/bsp_scenes.h"
#include "bsp/subdivision.h"
#include "bsp/subdivision_io.h"
#include "quake/prt_file.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

using namespace bsptest;

TEST(PortalFile, ReadsBackAsTheSameGraphOrientedBackToFront) {
  const Scene scene = twoRoomsWithDoor();
  const Subdivision sub = buildSubdivision(scene, BspOptions{});
  ASSERT_GT(sub.portals.size(), 3u);
  const auto path = test::scratchDir() / "cells.prt";
  writePortalsPrt(sub, path.string());
  const PrtFile prt = readPrtFile(path.string());
  EXPECT_EQ(prt.version, 1);
  EXPECT_EQ(prt.leafCount, sub.cells.size());
  ASSERT_EQ(prt.portals.size(), sub.portals.size());
  for (size_t k = 0; k < sub.portals.size(); ++k) {
    const Portal& p = sub.portals[k];
    const PrtPortal& q = prt.portals[k];
    EXPECT_EQ(q.clusterA, int(p.back));
    EXPECT_EQ(q.clusterB, int(p.front));
    ASSERT_EQ(q.winding.size(), p.polygon.vertices.size());
    for (size_t i = 0; i < q.winding.size(); ++i)
      EXPECT_EQ(q.winding[i], p.polygon.vertices[i]) << "portal " << k << " vertex " << i;
    // The reader's convention: the winding's counter-clockwise normal points from A into B. The
    // cells are convex and lie on either side of the portal's plane: B's centroid in front.
    Vec3 n{};
    for (size_t i = 0; i < q.winding.size(); ++i)
      n += cross(q.winding[i], q.winding[(i + 1) % q.winding.size()]);
    const Vec3& o = q.winding[0];
    EXPECT_GT(dot(n, sub.cells[p.front].shape.centroid() - o), 0) << "portal " << k;
    EXPECT_LT(dot(n, sub.cells[p.back].shape.centroid() - o), 0) << "portal " << k;
  }
}

}  // namespace
}  // namespace gv
