// OBJ/MTL import and export: materials, face provenance, round trip, and every kind of bad input
// ending in an InputError that names the file and the line.
#include <gtest/gtest.h>

#include <random>

#include "input/load_scene.h"
#include "scene/patches_obj.h"
#include "scene/scene_io.h"
#include "support/temp_dir.h"
#include "util/input_error.h"

namespace gv {
namespace {

using test::scratchDir;
using test::writeFile;

const char* kTwoFaces = R"(# a unit square and an L shape
mtllib room.mtl
v 0 0 0
v 1 0 0
v 1 1 0.0
v 0 1 0
v 0 0 1
v 2 0 1
v 2 1 1
v 1 1 1
v 1 2 1
v 0 2 1
usemtl white
f 1 2 3 4
usemtl lamp
f 5 6 7 8 9 10
)";
const char* kRoomMtl = "newmtl white\nKd 0.7 0.6 0.5\n\nnewmtl lamp\nKd 0.1 0.1 0.1\nKe 5 4 3\n";

TEST(ObjImport, ReadsMaterialsAndRemembersSourceFaces) {
  const auto dir = scratchDir();
  writeFile(dir / "room.mtl", kRoomMtl);
  const Scene s = importObj(writeFile(dir / "room.obj", kTwoFaces));
  EXPECT_EQ(s.report.facesIn, 2u);
  EXPECT_EQ(s.report.splitNonConvex, 1u);
  ASSERT_EQ(s.patches.size(), 3u);  // the L becomes two convex pieces
  EXPECT_EQ(s.patches[0].sourceFace, 0u);
  EXPECT_EQ(s.patches[1].sourceFace, 1u);
  EXPECT_EQ(s.patches[2].sourceFace, 1u);
  const Material& white = s.materials.at(s.patches[0].material);
  EXPECT_NEAR(white.reflectance.r, 0.7, 1e-15);  // tinyobjloader's parser may be 1 ulp off
  EXPECT_NEAR(white.reflectance.g, 0.6, 1e-15);
  EXPECT_NEAR(white.reflectance.b, 0.5, 1e-15);
  EXPECT_FALSE(white.isEmitter());
  const Material& lamp = s.materials.at(s.patches[1].material);
  EXPECT_EQ(lamp.emission, (Rgb{5, 4, 3}));
  EXPECT_EQ(s.emitterCount(), 2u);
  EXPECT_NEAR(s.totalArea(), 1.0 + 3.0, 1e-12);
  EXPECT_TRUE(s.report.warnings.empty());
}

TEST(ObjImport, MissingMtlGivesGreyAndAWarning) {
  const auto dir = scratchDir();
  const Scene s = importObj(writeFile(dir / "room.obj", kTwoFaces));
  ASSERT_EQ(s.patches.size(), 3u);
  for (const Patch& p : s.patches) {
    EXPECT_EQ(s.materials.at(p.material).reflectance, (Rgb{0.5, 0.5, 0.5}));
    EXPECT_FALSE(s.materials.at(p.material).isEmitter());
  }
  ASSERT_FALSE(s.report.warnings.empty());
  EXPECT_NE(s.report.warnings[0].find("room.obj:2"), std::string::npos) << s.report.warnings[0];
}

TEST(ObjImport, ExportThenImportGivesTheSamePatchesBitForBit) {
  const auto dir = scratchDir();
  writeFile(dir / "room.mtl", kRoomMtl);
  const Scene a = importObj(writeFile(dir / "room.obj", kTwoFaces));
  writeObj(a, (dir / "out" / "patches.obj").string());
  const Scene b = importObj((dir / "out" / "patches.obj").string());
  ASSERT_EQ(a.patches.size(), b.patches.size());
  for (size_t i = 0; i < a.patches.size(); ++i) {
    EXPECT_EQ(a.patches[i].polygon.vertices, b.patches[i].polygon.vertices) << "patch " << i;
    EXPECT_EQ(b.patches[i].sourceFace, i);  // exported face k is patch k
    const Material& ma = a.materials[a.patches[i].material];
    const Material& mb = b.materials[b.patches[i].material];
    EXPECT_NEAR(ma.reflectance.g, mb.reflectance.g, 1e-15);
    EXPECT_NEAR(ma.emission.r, mb.emission.r, 1e-15);
  }
}

TEST(ObjImport, PatchFilesKeepSliversThatUserInputDrops) {
  // A 1000-unit floor and, beside it, a triangle 0.01 wide (2 area / diameter): thinner than the
  // model tolerance (1e-5 of the diagonal, ~0.0141), so an OBJ from a user loses it, but the CSG
  // of .map files makes such pieces (e3m4.map: 33) and a patch file must read back face for face
  // (face k = patch k). A file whose faces are not one patch each is still refused.
  const auto dir = scratchDir();
  const Tolerance tol{1000};
  Scene a;
  a.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  for (const std::vector<Vec3>& v :
       std::vector<std::vector<Vec3>>{{{0, 0, 0}, {1000, 0, 0}, {1000, 1000, 0}, {0, 1000, 0}},
                                      {{0, -1, 0}, {500, -1.01, 0}, {500, -1, 0}}}) {
    auto poly = ConvexPolygon::fromVertices(v, tol);
    ASSERT_TRUE(poly);
    a.patches.push_back({*poly, 0, static_cast<uint32_t>(a.patches.size())});
  }
  const std::string path = (dir / "patches.obj").string();
  writeObj(a, path);
  EXPECT_EQ(importObj(path).patches.size(), 1u);  // the sliver dropped, as from a user
  const Scene b = importPatchesObj(path, "the test");
  ASSERT_EQ(b.patches.size(), 2u);
  EXPECT_EQ(b.patches[1].polygon.vertices, a.patches[1].polygon.vertices);
  const std::string lShape = writeFile(dir / "l.obj",
                                       "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
                                       "f 1 2 3 4 5 6\n");
  EXPECT_THROW(importPatchesObj(lShape, "the test"), InputError);
}

TEST(ObjImport, DegenerateFacesAreCountedNotFatal) {
  const auto dir = scratchDir();
  const Scene s = importObj(
      writeFile(dir / "d.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 1 1\n"));
  EXPECT_EQ(s.report.facesIn, 3u);
  EXPECT_EQ(s.report.droppedDegenerate, 2u);
  ASSERT_EQ(s.patches.size(), 1u);
  EXPECT_EQ(s.patches[0].sourceFace, 1u);
}

/// Imports `obj` (with an optional MTL) and returns the error message, or "" if none was thrown.
std::string importError(const std::string& obj, const std::string& mtl = "",
                        const std::string& name = "bad.obj") {
  const auto dir = scratchDir();
  if (!mtl.empty()) writeFile(dir / "bad.mtl", mtl);
  try {
    loadScene(writeFile(dir / name, obj));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(ObjImportBadInput, MissingFile) {
  try {
    loadScene("/nonexistent/scene.obj");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/scene.obj: file not found");
  }
}

TEST(ObjImportBadInput, NanAndInfCoordinatesNameTheLine) {
  EXPECT_NE(importError("v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n")
                .find("bad.obj:3: vertex coordinate 'nan' is not finite"),
            std::string::npos);
  EXPECT_NE(importError("v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n").find("bad.obj:2:"),
            std::string::npos);
  EXPECT_NE(importError("v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n").find("bad.obj:2:"),
            std::string::npos);
}

TEST(ObjImportBadInput, MalformedVertex) {
  EXPECT_NE(importError("v 0 0\n").find("bad.obj:1: vertex needs 3 coordinates"),
            std::string::npos);
  EXPECT_NE(importError("v 0 zero 0\n").find("bad.obj:1: vertex coordinate 'zero' is not a number"),
            std::string::npos);
}

TEST(ObjImportBadInput, BadFaceIndices) {
  EXPECT_NE(importError(std::string(kTriangle) + "f 1 2 9\n")
                .find("bad.obj:4: face vertex index 9 is out of range"),
            std::string::npos);
  EXPECT_NE(
      importError(std::string(kTriangle) + "f 0 1 2\n").find("bad.obj:4: face vertex index 0"),
      std::string::npos);
  EXPECT_NE(importError(std::string(kTriangle) + "f -1 -2 -4\n")
                .find("bad.obj:4: relative face vertex index -4"),
            std::string::npos);
  EXPECT_NE(importError(std::string(kTriangle) + "f 1 x 3\n")
                .find("bad.obj:4: face vertex 'x' is not an index"),
            std::string::npos);
}

TEST(ObjImportBadInput, FaceWithFewerThanThreeVertices) {
  EXPECT_NE(importError(std::string(kTriangle) + "f 1 2\n").find("bad.obj:4: face has 2 vertices"),
            std::string::npos);
}

TEST(ObjImportBadInput, EmptySceneAndAllDegenerate) {
  EXPECT_EQ(importError(""), std::string(scratchDir() / "bad.obj") + ": the scene has no faces");
  EXPECT_NE(importError("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").find("no usable face"),
            std::string::npos);
}

TEST(ObjImportBadInput, MalformedMtlNamesItsLine) {
  const std::string obj = "mtllib bad.mtl\n" + std::string(kTriangle) + "f 1 2 3\n";
  EXPECT_NE(importError(obj, "newmtl a\nKd 0.5 abc 0.5\n")
                .find("bad.mtl:2: Kd value 'abc' is not a number"),
            std::string::npos);
  EXPECT_NE(importError(obj, "newmtl a\nKe 1 nan 1\n").find("bad.mtl:2:"), std::string::npos);
  EXPECT_NE(importError(obj, "newmtl a\nKd -1 0 0\n").find("non-negative"), std::string::npos);
}

TEST(ObjImportBadInput, UnreadableMtlNamesTheObjLine) {
  const auto dir = scratchDir();
  std::filesystem::create_directories(dir / "lib.mtl");  // a directory where a file should be
  try {
    importObj(writeFile(dir / "x.obj",
                        "# header\nmtllib lib.mtl\n" + std::string(kTriangle) + "f 1 2 3\n"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.obj:2: material library unreadable"), std::string::npos)
        << e.what();
  }
}

TEST(ObjImport, CarriageReturnLineEndingsAreLineEnds) {
  // Found by the fuzzer: a lone "\r" ends a line for tinyobjloader, so it must for the precheck.
  const auto dir = scratchDir();
  const Scene s = importObj(writeFile(dir / "mac.obj", "v 0 0 0\rv 1 0 0\r\nv 0 1 0\rf 1 2 3\r"));
  EXPECT_EQ(s.patches.size(), 1u);
  EXPECT_NE(
      importError("mt\rf 1/1/1 2/ 1\n").find("bad.obj:2: face vertex index 1 is out of range"),
      std::string::npos)
      << importError("mt\rf 1/1/1 2/ 1\n");
}

TEST(ObjImportBadInput, UnsupportedExtension) {
  // .stl and the like now go through Assimp (assimp_import_test.cpp); an unknown extension is
  // refused.
  EXPECT_NE(importError("whatever", "", "scene.qqq").find("unsupported scene format '.qqq'"),
            std::string::npos);
}

}  // namespace
}  // namespace gv

namespace gv {
namespace {

TEST(ObjImport, RandomCoordinatesRoundTripExactly) {
  const auto dir = test::scratchDir();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  Scene a;
  a.addMaterial({"m", {0.25, 0.5, 0.75}, {}});
  for (int i = 0; i < 50; ++i) {
    const Vec3 o{u(rng), u(rng), u(rng)};
    const Vec3 e1{u(rng) * 1e-3, u(rng) * 1e-3, u(rng) * 1e-3};
    const Vec3 e2{u(rng) * 1e-3, u(rng) * 1e-3, u(rng) * 1e-3};
    auto tri = ConvexPolygon::fromVertices({o, o + e1, o + e2}, Tolerance{1e3});
    ASSERT_TRUE(tri.has_value());
    a.patches.push_back({*tri, 0, kNoSourceFace});
  }
  writeObj(a, (dir / "r.obj").string());
  const Scene b = importObj((dir / "r.obj").string());
  ASSERT_EQ(b.patches.size(), a.patches.size());
  for (size_t i = 0; i < a.patches.size(); ++i)
    EXPECT_EQ(a.patches[i].polygon.vertices, b.patches[i].polygon.vertices) << "patch " << i;
}

}  // namespace
}  // namespace gv
