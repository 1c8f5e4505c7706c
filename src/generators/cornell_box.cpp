// The Cornell box with its published measured geometry: the classic radiosity test scene.
// Source: Cornell University Program of Computer Graphics, "Cornell Box Data",
// https://www.graphics.cornell.edu/online/box/data.html (coordinates in mm, listed per face).
#include "generators/cornell_box.h"

#include <array>

#include "generators/scene_builder.h"

namespace gv {
namespace {

using Quad = std::array<Vec3, 4>;

// The published faces, in the published vertex order, which is counter-clockwise seen from the
// inside of the box (walls) and from the outside of the blocks.
constexpr Quad kFloor{{{552.8, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 559.2}, {549.6, 0.0, 559.2}}};
constexpr Quad kCeiling{
    {{556.0, 548.8, 0.0}, {556.0, 548.8, 559.2}, {0.0, 548.8, 559.2}, {0.0, 548.8, 0.0}}};
constexpr Quad kBackWall{
    {{549.6, 0.0, 559.2}, {0.0, 0.0, 559.2}, {0.0, 548.8, 559.2}, {556.0, 548.8, 559.2}}};
constexpr Quad kGreenWall{{{0.0, 0.0, 559.2}, {0.0, 0.0, 0.0}, {0.0, 548.8, 0.0}, {0.0, 548.8, 559.2}}};
constexpr Quad kRedWall{
    {{552.8, 0.0, 0.0}, {549.6, 0.0, 559.2}, {556.0, 548.8, 559.2}, {556.0, 548.8, 0.0}}};
// Not published (the real box is open there); used with closedFront. Its edges follow the floor's
// and ceiling's front edges.
constexpr Quad kFrontWall{{{0.0, 0.0, 0.0}, {552.8, 0.0, 0.0}, {556.0, 548.8, 0.0}, {0.0, 548.8, 0.0}}};
// Lowered by 0.5 mm from the published 548.8 (see the header).
constexpr double kLightY = 548.8 - 0.5;
constexpr Quad kLight{
    {{343.0, kLightY, 227.0}, {343.0, kLightY, 332.0}, {213.0, kLightY, 332.0}, {213.0, kLightY, 227.0}}};

// A block: its top quad (counter-clockwise from above) and height; the published side faces are
// the vertical quads over the top's edges, the bottom is the top's footprint on the floor.
struct Block {
  Quad top;
};
constexpr Block kShortBlock{
    {{{130.0, 165.0, 65.0}, {82.0, 165.0, 225.0}, {240.0, 165.0, 272.0}, {290.0, 165.0, 114.0}}}};
constexpr Block kTallBlock{
    {{{423.0, 330.0, 247.0}, {265.0, 330.0, 296.0}, {314.0, 330.0, 456.0}, {472.0, 330.0, 406.0}}}};

void addBlock(SceneBuilder& builder, const Block& block, uint32_t material) {
  const Quad& t = block.top;
  builder.addQuad(t[0], t[1], t[2], t[3], material);
  auto floorPoint = [](const Vec3& p) { return Vec3{p.x, 0.0, p.z}; };
  // The top is counter-clockwise from above, so for its edge i -> i+1 the outward side face is
  // counter-clockwise as (bottom i+1, top i+1, top i, bottom i) — the published faces are these
  // quads, up to the starting vertex.
  for (int i = 0; i < 4; ++i) {
    const Vec3& a = t[i];
    const Vec3& b = t[(i + 1) % 4];
    builder.addQuad(floorPoint(b), b, a, floorPoint(a), material);
  }
  // Bottom: the footprint, reversed so that it faces down (into the floor).
  builder.addQuad(floorPoint(t[3]), floorPoint(t[2]), floorPoint(t[1]), floorPoint(t[0]), material);
}

}  // namespace

Scene generateCornellBox(const CornellBoxOptions& options) {
  Scene scene;
  const uint32_t white = scene.addMaterial({"white", {0.725, 0.71, 0.68}, {}});
  const uint32_t red = scene.addMaterial({"red", {0.63, 0.065, 0.05}, {}});
  const uint32_t green = scene.addMaterial({"green", {0.14, 0.45, 0.091}, {}});
  const uint32_t light = scene.addMaterial({"light", {0.78, 0.78, 0.78}, {17.0, 12.0, 4.0}});

  Aabb box;
  box.add(Vec3{0, 0, 0});
  box.add(Vec3{556.0, 548.8, 559.2});
  SceneBuilder builder(scene, Tolerance::forBounds(box));
  auto add = [&](const Quad& q, uint32_t material) { builder.addQuad(q[0], q[1], q[2], q[3], material); };
  add(kFloor, white);
  add(kCeiling, white);
  add(kBackWall, white);
  add(kGreenWall, green);
  add(kRedWall, red);
  if (options.closedFront) add(kFrontWall, white);
  add(kLight, light);
  addBlock(builder, kShortBlock, white);
  addBlock(builder, kTallBlock, white);
  return scene;
}

}  // namespace gv
