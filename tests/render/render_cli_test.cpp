// `globalvis radiosity` pictures end to end: the PNGs exist, have the requested size and show
// something (not one colour); options are checked; the default cameras see into the scenes.
#include <gtest/gtest.h>

#include <set>

#include "generators/cornell_box.h"
#include "generators/office.h"
#include "render/default_camera.h"
#include "render/png_image.h"
#include "support/run_cli.h"
#include "support/temp_dir.h"

namespace gv {
namespace {

size_t distinctColours(const RgbImage& image) {
  std::set<uint32_t> colours;
  for (size_t i = 0; i + 2 < image.pixels.size(); i += 3)
    colours.insert((image.pixels[i] << 16) | (image.pixels[i + 1] << 8) | image.pixels[i + 2]);
  return colours.size();
}

constexpr const char* kPictures[] = {"render.png", "mesh.png", "links_visible.png",
                                     "links_partial.png"};

/// A quick (coarse) solve of the Cornell box.
std::string quickCornell(const std::filesystem::path& dir) {
  const test::CliResult gen = test::runCli("gen cornell -o '" + (dir / "c.obj").string() + "'");
  EXPECT_EQ(gen.exitCode, 0) << gen.output;
  return "radiosity '" + (dir / "c.obj").string() +
         "' -q --epsilon 1e-3 --max-refinements 3 --rays 4 -o '";
}

TEST(RenderCliTest, CornellPicturesHaveTheRequestedSizeAndContent) {
  const auto dir = test::scratchDir();
  const test::CliResult r =
      test::runCli(quickCornell(dir) + (dir / "out").string() + "' --image-size 160x120");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* name : kPictures) {
    SCOPED_TRACE(name);
    const RgbImage image = readPng((dir / "out" / name).string());
    EXPECT_EQ(image.width, 160);
    EXPECT_EQ(image.height, 120);
    EXPECT_GT(distinctColours(image), 20u);
  }
  // The default camera looks into the open front: the middle of the picture is the lit box,
  // not the background, and the light (top middle) is the brightest there is.
  const RgbImage render = readPng((dir / "out" / "render.png").string());
  const uint8_t* centre = render.at(80, 60);
  EXPECT_GT(centre[0] + centre[1] + centre[2], 3 * 60);
  // Link pictures: white lines over a dimmed picture: some pure white pixels on the visible one.
  const RgbImage visible = readPng((dir / "out" / "links_visible.png").string());
  size_t bright = 0;
  for (int y = 0; y < visible.height; ++y)
    for (int x = 0; x < visible.width; ++x) bright += visible.at(x, y)[2] > 200;
  EXPECT_GT(bright, 100u);
}

TEST(RenderCliTest, ExplicitCameraNoPicturesAndBadOptions) {
  const auto dir = test::scratchDir();
  const std::string base = quickCornell(dir);
  const test::CliResult r = test::runCli(base + (dir / "cam").string() +
                                         "' --image-size 64x48 --flat --camera "
                                         "278,273,-800,278,273,0,39");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(readPng((dir / "cam" / "render.png").string()).width, 64);
  const test::CliResult none = test::runCli(base + (dir / "none").string() + "' --no-pictures");
  ASSERT_EQ(none.exitCode, 0) << none.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "none" / "radiosity.txt"));
  EXPECT_FALSE(std::filesystem::exists(dir / "none" / "render.png"));
  EXPECT_EQ(test::runCli(base + (dir / "bad").string() + "' --camera 1,2,3").exitCode, 1);
  EXPECT_EQ(test::runCli(base + (dir / "bad").string() + "' --image-size 0x10").exitCode, 1);
  EXPECT_EQ(test::runCli(base + (dir / "bad").string() + "' --image-size 640").exitCode, 1);
}

size_t litPixels(const RgbImage& image) {
  size_t lit = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) lit += image.at(x, y)[0] + image.at(x, y)[1] > 2 * 100;
  return lit;
}

TEST(RenderCliTest, DefaultOfficePictureShowsLitRoomsThroughTheCutaway) {
  const auto dir = test::scratchDir();
  ASSERT_EQ(test::runCli("gen office -o '" + (dir / "o.obj").string() + "'").exitCode, 0);
  const std::string base = "radiosity '" + (dir / "o.obj").string() +
                           "' -q --epsilon 1e-3 --max-refinements 2 --rays 4 --image-size 200x150";
  const test::CliResult r = test::runCli(base + " -o '" + (dir / "out").string() + "'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const RgbImage image = readPng((dir / "out" / "render.png").string());
  EXPECT_GT(distinctColours(image), 50u);
  // The same viewpoint given by --camera has no cutaway: the picture is the unlit roof.
  const Camera c = defaultCamera(generateOffice({}), 200, 150);
  const std::string camera = std::to_string(c.eye.x) + "," + std::to_string(c.eye.y) + "," +
                             std::to_string(c.eye.z) + "," + std::to_string(c.target.x) + "," +
                             std::to_string(c.target.y) + "," + std::to_string(c.target.z);
  const test::CliResult roof =
      test::runCli(base + " --camera " + camera + " -o '" + (dir / "roof").string() + "'");
  ASSERT_EQ(roof.exitCode, 0) << roof.output;
  const size_t lit = litPixels(image);
  const size_t litWithRoof = litPixels(readPng((dir / "roof" / "render.png").string()));
  EXPECT_GT(lit, 200u * 150u / 10);
  EXPECT_LT(litWithRoof, 200u * 150u / 100);
}

TEST(RenderDefaultCameraTest, CornellLooksIntoTheOpenFrontAndOfficeLiftsTheRoof) {
  const Scene cornell = generateCornellBox({});
  const Camera c = defaultCamera(cornell, 800, 600);
  EXPECT_LT(c.eye.z, 0);  // in front of the open side z = 0
  EXPECT_GT(c.forward().z, 0.99);
  EXPECT_FALSE(c.cutaway);
  const Aabb box = cornell.bounds();
  // The whole open front (z = 0) is in the picture.
  for (const Vec3& corner : {Vec3{box.lo.x, box.lo.y, 0}, Vec3{box.hi.x, box.hi.y, 0}}) {
    const auto p = c.project(corner);
    ASSERT_TRUE(p);
    EXPECT_GE(p->x, 0);
    EXPECT_LE(p->x, 800);
    EXPECT_GE(p->y, 0);
    EXPECT_LE(p->y, 600);
  }

  const OfficeOptions options;
  const Scene office = generateOffice(options);
  const Camera o = defaultCamera(office, 800, 600);
  ASSERT_TRUE(o.cutaway);
  EXPECT_NEAR(o.cutaway->normal.z, 1, 1e-12);  // z is up in the office
  // The cut is below the ceiling of the room interiors and above their floors.
  const Aabb room = officeRoomInterior(options, 0, 0, 0);
  EXPECT_LT(o.cutaway->offset, room.hi.z);
  EXPECT_GT(o.cutaway->offset, room.lo.z + 0.8 * (room.hi.z - room.lo.z));
  EXPECT_GT(o.eye.z, office.bounds().hi.z);  // looking down from above
  EXPECT_LT(o.forward().z, -0.5);
}

}  // namespace
}  // namespace gv
