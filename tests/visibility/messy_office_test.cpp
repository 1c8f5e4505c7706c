// Visibility on messy input: the default office written out as OBJ with the defects real levels
// have (coplanar overlapping duplicates, T-junction splits, sliver triangles, cracks from vertex
// jitter), read back through the importer, and checked by `verify`'s independent ray casting.
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "bsp/subdivision.h"
#include "generators/office.h"
#include "input/load_scene.h"
#include "scene/scene_io.h"
#include "support/temp_dir.h"
#include "visibility/propagation.h"
#include "visibility/verify.h"

namespace gv {
namespace {

Vec3 lerp(const Vec3& a, const Vec3& b, double t) {
  return a + (b - a) * t;
}

// Writes `scene`'s faces as OBJ with defects drawn from `seed` (about 28 % of the faces touched),
// referencing the MTL that writeObj wrote beside `clean`.
void writeMessyObj(const Scene& scene, const std::filesystem::path& clean,
                   const std::filesystem::path& out, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  // Jitter of 2e-5 in a scene of diagonal ~22: about 1e-6 of its size, far above the
  // importer's and the BSP's tolerances.
  std::uniform_real_distribution<double> jitter(-2e-5, 2e-5);
  std::ofstream obj(out);
  obj.precision(9);
  obj << "mtllib " << clean.stem().string() << ".mtl\n";
  size_t next = 1;
  auto face = [&](const std::string& material, const std::vector<Vec3>& v) {
    obj << "usemtl " << material << "\n";
    for (const Vec3& p : v) obj << "v " << p.x << " " << p.y << " " << p.z << "\n";
    obj << "f";
    for (size_t k = 0; k < v.size(); ++k) obj << " " << next + k;
    obj << "\n";
    next += v.size();
  };
  for (const Patch& patch : scene.patches) {
    const std::string& m = scene.materials[patch.material].name;
    const std::vector<Vec3>& v = patch.polygon.vertices;
    const double r = u(rng);
    if (r < 0.08) {  // a coplanar duplicate
      face(m, v);
      face(m, v);
    } else if (r < 0.16 && v.size() == 4) {  // split in two, one edge split: a T-junction
      const double t = 0.2 + 0.6 * u(rng);
      const Vec3 p = lerp(v[0], v[1], t), q = lerp(v[3], v[2], t);
      face(m, {v[0], p, q, v[3]});
      face(m, {p, v[1], v[2], q});
    } else if (r < 0.22 && v.size() == 4) {  // a sliver triangle along an edge
      const Vec3 e = lerp(v[0], v[1], 1e-4);
      face(m, {v[0], e, v[3]});
      face(m, {e, v[1], v[2], v[3]});
    } else if (r < 0.28) {  // cracks: every vertex moved a little
      std::vector<Vec3> moved = v;
      for (Vec3& p : moved) p += Vec3{jitter(rng), jitter(rng), jitter(rng)};
      face(m, moved);
    } else {
      face(m, v);
    }
  }
}

TEST(MessyOffice, VerifyFindsNoViolationOnDuplicatesTJunctionsSliversAndCracks) {
  const auto dir = test::scratchDir();
  const Scene office = generateOffice();
  const auto clean = dir / "office.obj";
  writeObj(office, clean.string());
  // Seeds that failed before the plane merging judged a face by its vertices (plane_set.cpp):
  // 7 lost 782 pairs of one room (its wall split across two planes 1e-5 apart), 14 and 33 had
  // blocked VISIBLE pairs, 21 a missing blocker; 2 has hits behind a listed blocker met within
  // verify's contact distance.
  for (uint64_t seed : {2, 7, 14, 21, 33}) {
    const auto messy = dir / ("messy" + std::to_string(seed) + ".obj");
    writeMessyObj(office, clean, messy, seed);
    const Scene scene = loadScene(messy.string());
    EXPECT_GT(scene.patches.size(), office.patches.size()) << seed;
    BspOptions bsp;
    bsp.minCoverage = kVisibilityMinCoverage;
    const VisibilityGraph graph = computeVisibility(scene, buildSubdivision(scene, bsp));
    VerifyOptions o;
    o.rays = 100000;
    o.segments = 40000;
    o.seed = static_cast<uint32_t>(seed);
    const VerifyReport r = verifyVisibility(scene, graph, o);
    EXPECT_GT(r.blockedSegments, 5000u) << seed;
    EXPECT_TRUE(r.ok()) << seed << ": " << (r.examples.empty() ? "" : r.examples[0]);
  }
}

}  // namespace
}  // namespace gv
