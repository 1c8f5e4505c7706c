// Tests of mesh import through Assimp: a PLY and a glTF written here, read back as patches with
// the known areas, orientation and material colours; unreadable files are InputErrors.
#include <gtest/gtest.h>

#include <cstring>

#include "input/load_scene.h"
#include "support/temp_dir.h"
#include "util/input_error.h"

namespace gv {
namespace {

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = static_cast<uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<uint8_t>(bytes[i + 2]);
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[v & 63] : '=';
  }
  return out;
}

template <typename T>
void append(std::string& bytes, T value) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  bytes.append(b, sizeof(T));
}

TEST(AssimpImport, PlyPolygonBecomesConvexPatches) {
  const auto dir = test::scratchDir();
  // An L-shaped hexagon of area 3 in z = 1, counter-clockwise seen from +z.
  const std::string path =
      test::writeFile(dir / "ell.ply",
                      "ply\nformat ascii 1.0\nelement vertex 6\n"
                      "property float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\n"
                      "end_header\n0 0 1\n2 0 1\n2 1 1\n1 1 1\n1 2 1\n0 2 1\n"
                      "6 0 1 2 3 4 5\n");
  const Scene s = loadScene(path);
  EXPECT_EQ(s.report.facesIn, 1u);
  EXPECT_EQ(s.report.splitNonConvex, 1u);
  EXPECT_GE(s.patches.size(), 2u);
  EXPECT_NEAR(s.totalArea(), 3, 1e-12);
  for (const Patch& p : s.patches) {
    EXPECT_NEAR(p.polygon.normal().z, 1, 1e-12);
    EXPECT_EQ(p.sourceFace, 0u);
    EXPECT_EQ(s.materials[p.material].reflectance, (Rgb{0.5, 0.5, 0.5}));
    EXPECT_FALSE(s.materials[p.material].isEmitter());
  }
}

TEST(AssimpImport, GltfMeshWithTransformAndEmissiveMaterial) {
  const auto dir = test::scratchDir();
  std::string bin;
  for (float v : {0.f, 0.f, 0.f, 2.f, 0.f, 0.f, 2.f, 1.f, 0.f, 0.f, 1.f, 0.f}) append(bin, v);
  for (int i : {0, 1, 2, 0, 2, 3}) append(bin, static_cast<uint16_t>(i));
  const std::string gltf = R"({
  "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "translation": [0, 0, 5]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "materials": [{"name": "lamp", "pbrMetallicRoughness": {"baseColorFactor": [0.25, 0.5, 0.75, 1]},
                 "emissiveFactor": [1, 0.5, 0.25]}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
                           base64(bin) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [0, 0, 0], "max": [2, 1, 0]},
                {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]
})";
  const Scene s = loadScene(test::writeFile(dir / "quad.gltf", gltf));
  ASSERT_EQ(s.patches.size(), 2u);
  EXPECT_NEAR(s.totalArea(), 2, 1e-6);
  for (const Patch& p : s.patches) {
    EXPECT_NEAR(p.polygon.normal().z, 1, 1e-12);
    for (const Vec3& v : p.polygon.vertices) EXPECT_EQ(v.z, 5);
    const Material& m = s.materials[p.material];
    EXPECT_NEAR(m.reflectance.r, 0.25, 1e-6);
    EXPECT_NEAR(m.reflectance.g, 0.5, 1e-6);
    EXPECT_NEAR(m.reflectance.b, 0.75, 1e-6);
    EXPECT_NEAR(m.emission.r, 1, 1e-6);
    EXPECT_NEAR(m.emission.g, 0.5, 1e-6);
    EXPECT_NEAR(m.emission.b, 0.25, 1e-6);
  }
  EXPECT_EQ(s.emitterCount(), 2u);
}

TEST(AssimpImport, UnreadableFilesNameTheFile) {
  const auto dir = test::scratchDir();
  const std::string junk = test::writeFile(dir / "junk.ply", "this is not a ply file\n");
  for (const std::string& path :
       {junk, (dir / "missing.glb").string(), test::writeFile(dir / "x.qqq", "x")}) {
    try {
      loadScene(path);
      ADD_FAILURE() << path;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace gv
