// The picture pipeline (paper §7.4 pictures): PNG round trip, camera projection against hand
// values, one-sided ray casting, tone mapping of a known radiance, depth-tested segments.
#include "render/render.h"

#include <gtest/gtest.h>

#include "generators/scene_builder.h"
#include "radiosity/element_mesh.h"
#include "render/camera.h"
#include "render/element_bvh.h"
#include "render/png_image.h"
#include "render/segment_drawing.h"
#include "render/tone_map.h"
#include "support/temp_dir.h"
#include "util/input_error.h"

namespace gv {
namespace {

/// Quads given counter-clockwise from their front.
struct Quad {
  Vec3 a, b, c, d;
};

Scene sceneOf(const std::vector<Quad>& quads) {
  Scene scene;
  const uint32_t m = scene.addMaterial({"m", {0.5, 0.5, 0.5}, {}});
  Aabb box;
  for (const Quad& q : quads) box.add(q.a), box.add(q.b), box.add(q.c), box.add(q.d);
  SceneBuilder builder(scene, Tolerance::forBounds(box));
  for (const Quad& q : quads) builder.addQuad(q.a, q.b, q.c, q.d, m);
  return scene;
}

/// A solution without solving: patch k has radiosity `b[k]`, no links, no children.
RadiosityResult resultOf(const Scene& scene, const std::vector<Rgb>& b) {
  return RadiosityResult{b, b, ElementTree(scene), {}, {}};
}

/// Camera at the origin looking down -z, y up, 90° vertical field of view.
Camera straightCamera(int w, int h) {
  Camera c;
  c.eye = {0, 0, 0};
  c.target = {0, 0, -1};
  c.up = {0, 1, 0};
  c.fovYDegrees = 90;
  c.width = w;
  c.height = h;
  return c;
}

struct Rendered {
  Scene scene;
  RadiosityResult result;
  ElementMesh mesh;
  RenderBuffers buffers;
  Rendered(const std::vector<Quad>& quads, const std::vector<Rgb>& b)
      : scene(sceneOf(quads)), result(resultOf(scene, b)), mesh(buildElementMesh(result)) {}
};

Rendered render(const std::vector<Quad>& quads, const std::vector<Rgb>& b, const Camera& camera) {
  Rendered r(quads, b);
  const ElementBvh bvh(r.mesh, r.result.elements);
  r.buffers = renderRadiosity(r.result, r.mesh, bvh, camera);
  return r;
}

size_t covered(const RenderBuffers& b) {
  size_t n = 0;
  for (uint32_t f : b.face) n += f != kNoFace;
  return n;
}

// A big quad at z = -1, counter-clockwise seen from +z (facing the camera at the origin).
const Quad kFacingWall{{-10, -10, -1}, {10, -10, -1}, {10, 10, -1}, {-10, 10, -1}};
const Quad kAwayWall{{-10, -10, -1}, {-10, 10, -1}, {10, 10, -1}, {10, -10, -1}};

TEST(RenderPngTest, RoundTripKeepsEveryByte) {
  const auto dir = test::scratchDir();
  RgbImage image(7, 5);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = static_cast<uint8_t>((i * 37 + 11) % 256);
  writePng(image, (dir / "a.png").string());
  const RgbImage back = readPng((dir / "a.png").string());
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.pixels, image.pixels);
  // Independent of libpng's reader: the signature and IHDR width/height, big-endian.
  std::ifstream in(dir / "a.png", std::ios::binary);
  std::vector<unsigned char> head(24);
  in.read(reinterpret_cast<char*>(head.data()), 24);
  EXPECT_EQ(head[0], 0x89);
  EXPECT_EQ(std::string(head.begin() + 1, head.begin() + 4), "PNG");
  EXPECT_EQ(std::string(head.begin() + 12, head.begin() + 16), "IHDR");
  EXPECT_EQ((head[16] << 24) | (head[17] << 16) | (head[18] << 8) | head[19], 7);
  EXPECT_EQ((head[20] << 24) | (head[21] << 16) | (head[22] << 8) | head[23], 5);
}

TEST(RenderPngTest, NotAPngIsAnInputError) {
  const auto dir = test::scratchDir();
  const std::string path = test::writeFile(dir / "x.png", "hello");
  EXPECT_THROW(readPng(path), InputError);
  EXPECT_THROW(readPng((dir / "missing.png").string()), InputError);
  EXPECT_THROW(writePng(RgbImage(2, 2), (dir / "no" / "such" / "dir.png").string()), InputError);
}

TEST(RenderCameraTest, ProjectsAKnownPointOntoTheHandComputedPixel) {
  // 90° vertical fov, 200x100 (aspect 2): a point at depth 2 with x = 1, y = 0.5 is at a
  // quarter of the half-width right of centre and a quarter of the half-height above it:
  // x = 100 + 0.25 * 100 = 125, y = 50 - 0.25 * 50 = 37.5.
  const Camera c = straightCamera(200, 100);
  const std::optional<PixelPoint> p = c.project({1, 0.5, -2});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->x, 125, 1e-9);
  EXPECT_NEAR(p->y, 37.5, 1e-9);
  EXPECT_NEAR(p->depth, 2, 1e-12);
  EXPECT_FALSE(c.project({0, 0, 1}));  // behind the eye
  // The ray through that image position goes through the point.
  const CameraRay r = c.ray(125, 37.5);
  const Vec3 expected = normalize(Vec3{1, 0.5, -2});
  EXPECT_NEAR(length(r.direction - expected), 0, 1e-12);
  // The image centre looks at the target.
  EXPECT_NEAR(length(c.ray(100, 50).direction - Vec3{0, 0, -1}), 0, 1e-12);
}

TEST(RenderCameraTest, ParsesEyeTargetAndFieldOfView) {
  Camera base;
  base.width = 64;
  base.height = 32;
  const Camera c = parseCamera("1,2,3, 4,5,6,30", base);
  EXPECT_EQ(c.eye, (Vec3{1, 2, 3}));
  EXPECT_EQ(c.target, (Vec3{4, 5, 6}));
  EXPECT_EQ(c.fovYDegrees, 30);
  EXPECT_EQ(c.width, 64);
  // Looking straight down the default up: another up is chosen.
  const Camera down = parseCamera("0,10,0,0,0,0");
  EXPECT_GT(length(cross(down.forward(), down.up)), 0.5);
  EXPECT_THROW(parseCamera("1,2,3,4,5"), std::invalid_argument);
  EXPECT_THROW(parseCamera("1,2,3,4,5,x"), std::invalid_argument);
  EXPECT_THROW(parseCamera("1,2,3,1,2,3"), std::invalid_argument);
  EXPECT_THROW(parseCamera("0,0,0,0,0,-1,190"), std::invalid_argument);
}

TEST(RenderTest, EmissiveQuadFillingTheViewGivesTheToneMappedValue) {
  const Rendered r = render({kFacingWall}, {{2, 1, 0.5}}, straightCamera(40, 30));
  ASSERT_EQ(covered(r.buffers), 40u * 30u);
  const size_t centre = r.buffers.index(20, 15);
  EXPECT_NEAR(r.buffers.depth[centre], 1.0, 1e-6);
  EXPECT_NEAR(r.buffers.radiance[centre].r, 2, 1e-12);
  // Automatic exposure: the 99th percentile of max(R,G,B) is 2 everywhere, so the channels map
  // to 1, 0.5 and 0.25 before sRGB: 255, round(255 (1.055 0.5^(1/2.4) - 0.055)) = 188 and
  // round(255 (1.055 0.25^(1/2.4) - 0.055)) = 137.
  EXPECT_DOUBLE_EQ(automaticWhite(r.buffers), 2);
  const RgbImage auto_ = toneMap(r.buffers);
  EXPECT_EQ(auto_.at(20, 15)[0], 255);
  EXPECT_EQ(auto_.at(20, 15)[1], 188);
  EXPECT_EQ(auto_.at(20, 15)[2], 137);
  // Fixed exposure 4: 0.5, 0.25, 0.125 -> 188, 137, 99; and one brighter than white clamps.
  const RgbImage fixed = toneMap(r.buffers, 4);
  EXPECT_EQ(fixed.at(0, 0)[0], 188);
  EXPECT_EQ(fixed.at(0, 0)[1], 137);
  EXPECT_EQ(fixed.at(0, 0)[2], 99);
  EXPECT_EQ(toneMap(r.buffers, 0.5).at(3, 3)[1], 255);
  EXPECT_EQ(encodeSrgb(0.001), 3);  // linear segment: round(255 * 12.92 * 0.001 = 3.29)
}

TEST(RenderTest, AutomaticExposureIgnoresTheFacesItIsToldTo) {
  // Left half of the view: a "light" of radiosity 100; right half: a wall of 0.5. Counting only
  // the wall, 0.5 maps to white and the light clamps; unfiltered, the light (half the pixels)
  // is the 99th percentile.
  const Quad light{{-10, -10, -1}, {0, -10, -1}, {0, 10, -1}, {-10, 10, -1}};
  const Quad wall{{0, -10, -1}, {10, -10, -1}, {10, 10, -1}, {0, 10, -1}};
  const Rendered r =
      render({light, wall}, {{100, 100, 100}, {0.5, 0.5, 0.5}}, straightCamera(40, 30));
  const auto lightFace = r.buffers.face[r.buffers.index(5, 15)];
  ASSERT_NE(lightFace, r.buffers.face[r.buffers.index(35, 15)]);
  EXPECT_DOUBLE_EQ(automaticWhite(r.buffers, [&](uint32_t f) { return f != lightFace; }), 0.5);
  EXPECT_DOUBLE_EQ(automaticWhite(r.buffers), 100);
  // Nothing counts: all faces do.
  EXPECT_DOUBLE_EQ(automaticWhite(r.buffers, [](uint32_t) { return false; }), 100);
  const RgbImage image = toneMap(r.buffers, 0.5);
  EXPECT_EQ(image.at(5, 15)[0], 255);
  EXPECT_EQ(image.at(35, 15)[0], 255);
}

TEST(RenderTest, BackFacesAreCulledSoAWallSeenFromBehindIsTransparent) {
  const Rendered away = render({kAwayWall}, {{1, 1, 1}}, straightCamera(20, 20));
  EXPECT_EQ(covered(away.buffers), 0u);
  const RgbImage image = toneMap(away.buffers);
  EXPECT_EQ(image.at(10, 10)[0], kBackground[0]);
  // A facing wall further back is seen through it.
  const Quad far{{-10, -10, -3}, {10, -10, -3}, {10, 10, -3}, {-10, 10, -3}};
  const Rendered both =
      render({kAwayWall, far}, {{1, 1, 1}, {0.5, 0.5, 0.5}}, straightCamera(20, 20));
  EXPECT_EQ(covered(both.buffers), 400u);
  EXPECT_NEAR(both.buffers.depth[both.buffers.index(10, 10)], 3.0, 1e-5);
  EXPECT_NEAR(both.buffers.radiance[both.buffers.index(10, 10)].g, 0.5, 1e-12);
}

TEST(RenderTest, SmallQuadCoversExactlyThePixelsOfItsHandProjection) {
  // Quad x, y in [0, 1] at z = -2: with 90° fov and 100x100 it spans x in [50, 75] and
  // y in [25, 50] (pixels), so the pixel centres 50.5..74.5 by 25.5..49.5 see it: 25 x 25.
  const Quad q{{0, 0, -2}, {1, 0, -2}, {1, 1, -2}, {0, 1, -2}};
  const Rendered r = render({q}, {{1, 1, 1}}, straightCamera(100, 100));
  EXPECT_EQ(covered(r.buffers), 625u);
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      const bool inside = x >= 50 && x < 75 && y >= 25 && y < 50;
      ASSERT_EQ(r.buffers.face[r.buffers.index(x, y)] != kNoFace, inside) << x << "," << y;
    }
}

TEST(RenderTest, CutawayRemovesWhatIsInFrontOfItsPlane) {
  const Quad far{{-10, -10, -3}, {10, -10, -3}, {10, 10, -3}, {-10, 10, -3}};
  Camera c = straightCamera(10, 10);
  c.cutaway = Plane{{0, 0, 1}, -2};  // removes z > -2: the near wall
  const Rendered r = render({kFacingWall, far}, {{1, 0, 0}, {0, 1, 0}}, c);
  EXPECT_EQ(covered(r.buffers), 100u);
  EXPECT_NEAR(r.buffers.depth[r.buffers.index(5, 5)], 3.0, 1e-5);
  // Facing the other way the plane removes everything behind z = -2 and keeps the eye's side.
  c.cutaway = Plane{{0, 0, -1}, 2};  // removes z < -2
  const Rendered near = render({kFacingWall, far}, {{1, 0, 0}, {0, 1, 0}}, c);
  EXPECT_NEAR(near.buffers.depth[near.buffers.index(5, 5)], 1.0, 1e-5);
}

TEST(RenderSegmentTest, DepthTestHidesSegmentsBehindSurfaces) {
  const Camera c = straightCamera(100, 100);
  const Quad q{{0, 0, -2}, {1, 0, -2}, {1, 1, -2}, {0, 1, -2}};  // pixels x 50..75, y 25..50
  const Rendered r = render({q}, {{0, 0, 0}}, c);
  RgbImage image = toneMap(r.buffers);
  // A horizontal segment at y = 0.5, z = -4 (behind the quad): projects to row 50 - 0.125·50
  // = 43.75, x from 50 - 0.25·50 = 37.5 to 50 + 0.75·50 = 87.5; drawn where the quad is not.
  const SegmentStyle white{{255, 255, 255}, 1, true};
  drawSegment(image, c, r.buffers.depth, {-1, 0.5, -4}, {3, 0.5, -4}, white);
  EXPECT_EQ(image.at(40, 43)[0], 255);  // background pixel: drawn
  EXPECT_EQ(image.at(80, 43)[0], 255);
  EXPECT_NE(image.at(60, 43)[0], 255);  // behind the quad: hidden
  // Without the depth test it is drawn across the quad too.
  SegmentStyle always = white;
  always.depthTest = false;
  drawSegment(image, c, r.buffers.depth, {-1, 0.5, -4}, {3, 0.5, -4}, always);
  EXPECT_EQ(image.at(60, 43)[0], 255);
  // A segment lying on the quad is visible (the slack), one crossing behind the eye is clipped.
  // (row 50 - 0.15·50 = 42.5, x 52.5 .. 72.5)
  drawSegment(image, c, r.buffers.depth, {0.1, 0.3, -2}, {0.9, 0.3, -2}, white);
  EXPECT_EQ(image.at(62, 42)[1], 255);
  drawSegment(image, c, r.buffers.depth, {0, -0.5, 1}, {0, -0.5, -1}, white);
  EXPECT_EQ(image.at(50, 99)[0], 255);  // the part in front of the eye reaches the bottom edge
}

}  // namespace
}  // namespace gv
