// The cell graph written as a Quake portal file (bsp/subdivision_io.h: writePortalsPrt): read back
// by the project's own .prt reader it is the same graph, oriented as qbsp orients its portals, and
// `globalvis pvs` runs on what `globalvis cells` writes.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "bsp/bsp_scenes.h"
#include "bsp/subdivision.h"
#include "bsp/subdivision_io.h"
#include "quake/prt_file.h"
#include "support/run_cli.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

using namespace bsptest;

Vec3 centroid(const ConvexPolyhedron& shape) {
  Vec3 sum{};
  size_t n = 0;
  for (const auto& face : shape.faces)
    for (const Vec3& v : face.polygon.vertices) sum += v, ++n;
  return sum / double(n);
}

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
    EXPECT_GT(dot(n, centroid(sub.cells[p.front].shape) - o), 0) << "portal " << k;
    EXPECT_LT(dot(n, centroid(sub.cells[p.back].shape) - o), 0) << "portal " << k;
  }
}

TEST(PortalFile, CellsWritesOneThatPvsReads) {
  const auto dir = test::scratchDir();
  const std::string obj = (dir / "office.obj").string();
  auto r = test::runCliStdout("gen office -o '" + obj + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = test::runCliStdout("cells '" + obj + "' -o '" + (dir / "out").string() + "' --json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto cells = nlohmann::json::parse(r.output);
  r = test::runCliStdout("pvs '" + (dir / "out" / "cells.prt").string() + "' -o '" +
                         (dir / "pvs.txt").string() + "' --json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto pvs = nlohmann::json::parse(r.output);
  EXPECT_EQ(pvs.at("leafs").get<size_t>(), cells.at("leaf_cells").get<size_t>());
  EXPECT_EQ(pvs.at("portals").get<size_t>(), cells.at("portals").get<size_t>());
  // Sealed offices: no cell sees them all, every cell sees itself and a neighbour at least.
  const double mean = pvs.at("mean_leafs_visible").get<double>();
  EXPECT_GT(mean, 1.0);
  EXPECT_LT(mean, 0.5 * cells.at("leaf_cells").get<double>());
}

}  // namespace
}  // namespace gv
