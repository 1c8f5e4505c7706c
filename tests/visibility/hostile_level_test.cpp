// Visibility on the hostile input real levels bring (issue #17): a level open to the sky with no
// inside, a level inside a sky box a thousand times its size, and degenerate faces among good
// ones. Each goes through the OBJ importer as a user's file would, must finish well inside a
// deadline (a hang would show as PropagationDeadlineExceeded, not as a stuck test), and must
// pass `verify`'s independent ray casting: a conservative answer, never a missing pair.
#include <gtest/gtest.h>

#include <fstream>

#include "bsp/subdivision.h"
#include "generators/office.h"
#include "input/load_scene.h"
#include "scene/scene_io.h"
#include "support/temp_dir.h"
#include "util/timing.h"
#include "visibility/propagation.h"
#include "visibility/verify.h"

namespace gv {
namespace {

/// Far more than any of these scenes needs (each takes well under a second in Release): only a
/// search that fans out without bound reaches it, and the test then fails instead of hanging.
constexpr double kDeadlineSeconds = 120;

/// `vis`'s defaults (its choice of cells) on `path`, under the deadline, then verify: the figures a
/// test asserts on.
struct Checked {
  Scene scene;
  VisibilityGraph graph;
  VerifyReport report;
};

Checked visAndVerify(const std::filesystem::path& path) {
  Checked c;
  c.scene = loadScene(path.string());
  PropagationOptions options;
  options.deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(kDeadlineSeconds));
  c.graph = computeVisibility(c.scene, buildVisibilitySubdivision(c.scene, {}), options);
  VerifyOptions v;
  v.rays = 100000;
  v.segments = 20000;
  c.report = verifyVisibility(c.scene, c.graph, v);
  return c;
}

/// The default office written as OBJ + MTL, without the patches `drop` names the material of.
std::filesystem::path writeOffice(const std::filesystem::path& dir, const std::string& drop) {
  Scene office = generateOffice();
  std::erase_if(office.patches, [&](const Patch& p) {
    return !drop.empty() && office.materials[p.material].name == drop;
  });
  const auto path = dir / "office.obj";
  writeObj(office, path.string());
  return path;
}

TEST(HostileLevel, OpenToTheSkyWithNoInsideIsConservative) {
  // No ceilings: every room opens upward onto nothing, so there is no closed inside for the
  // cells to follow, and rays leave the scene.
  const auto dir = test::scratchDir();
  const Checked c = visAndVerify(writeOffice(dir, "ceiling"));
  EXPECT_GT(c.graph.interactions.size(), 1000u);
  EXPECT_GT(c.report.raysHittingFront, 10000u);
  EXPECT_TRUE(c.report.ok()) << (c.report.examples.empty() ? "" : c.report.examples[0]);
}

TEST(HostileLevel, HugeSkyBoxAroundTheLevelIsConservative) {
  // An emitting box 1000x the office's size around it, facing in: the scene's tolerance (relative
  // to its size) grows a thousandfold, and the office becomes a speck inside the root cell.
  const auto dir = test::scratchDir();
  const auto path = writeOffice(dir, "");
  const Aabb b = loadScene(path.string()).bounds();
  const Vec3 c = b.center();
  const double h = 1000 * b.diagonal();
  {
    std::ofstream mtl(dir / "office.mtl", std::ios::app);
    mtl << "\nnewmtl sky\nKd 0 0 0\nKe 1 1 1\n";
    std::ofstream obj(path, std::ios::app);
    obj.precision(17);
    obj << "usemtl sky\n";
    auto v = [&](double x, double y, double z) {
      obj << "v " << c.x + x * h << " " << c.y + y * h << " " << c.z + z * h << "\n";
    };
    // The eight corners, then six faces wound to face the inside.
    for (int k = 0; k < 8; ++k) v(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
    const char* faces[] = {"f -8 -6 -2 -4", "f -7 -5 -1 -3", "f -8 -4 -3 -7",
                           "f -6 -5 -1 -2", "f -8 -7 -5 -6", "f -4 -2 -1 -3"};
    for (const char* f : faces) obj << f << "\n";
  }
  const Checked result = visAndVerify(path);
  std::printf("sky box: %zu patches, %zu pairs listed, %llu rays hit a front\n",
              result.scene.patches.size(), result.graph.interactions.size(),
              (unsigned long long)result.report.raysHittingFront);
  size_t sky = 0;
  for (const Patch& p : result.scene.patches)
    if (result.scene.materials[p.material].name == "sky") ++sky;
  ASSERT_EQ(sky, 6u);
  EXPECT_TRUE(result.report.ok()) << (result.report.examples.empty() ? ""
                                                                     : result.report.examples[0]);
  // The sky box sees the office's outside: some pairs with sky faces are listed.
  size_t skyPairs = 0;
  for (const Interaction& in : result.graph.interactions)
    if (result.scene.materials[result.scene.patches[in.r].material].name == "sky") ++skyPairs;
  EXPECT_GT(skyPairs, 0u);
}

TEST(HostileLevel, DegenerateFacesAreDroppedAndCountedAndTheRestIsConservative) {
  // Zero-area faces of every kind real exports contain, among the office's good ones.
  const auto dir = test::scratchDir();
  const auto path = writeOffice(dir, "");
  const size_t good = loadScene(path.string()).patches.size();
  {
    std::ofstream obj(path, std::ios::app);
    obj << "v 1 1 1\nv 2 1 1\nv 3 1 1\nv 1 1 1\n";
    obj << "f -4 -3 -2\n";     // collinear
    obj << "f -4 -1 -3\n";     // a repeated position
    obj << "f -4 -4 -3\n";     // a repeated index
    obj << "f -4 -3 -2 -1\n";  // collinear quad
  }
  const Checked c = visAndVerify(path);
  EXPECT_EQ(c.scene.patches.size(), good);
  EXPECT_EQ(c.scene.report.droppedDegenerate, 4u);
  EXPECT_TRUE(c.report.ok()) << (c.report.examples.empty() ? "" : c.report.examples[0]);
}

}  // namespace
}  // namespace gv
