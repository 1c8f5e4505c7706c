// A random perfect maze: a densely occluded floor plan where almost every cell hides the others.
#include "generators/maze.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "generators/scene_builder.h"
#include "generators/seeded_random.h"

namespace gv {
namespace {

// Light panels hang this far below the ceiling: not coplanar with it.
constexpr double kLightDrop = 0.02;
constexpr double kLightSize = 0.6;

// Which walls stand: the grid's edges minus the passages carved by the depth-first search.
struct MazeWalls {
  int width, height;
  std::vector<char> alongX;  ///< edge (i, j): x in [i, i+1] on line y = j; (width) x (height+1)
  std::vector<char> alongY;  ///< edge (i, j): y in [j, j+1] on line x = i; (width+1) x (height)

  MazeWalls(int w, int h)
      : width(w),
        height(h),
        alongX(static_cast<size_t>(w) * (h + 1), 1),
        alongY(static_cast<size_t>(w + 1) * h, 1) {}
  char& xEdge(int i, int j) { return alongX[static_cast<size_t>(j) * width + i]; }
  char& yEdge(int i, int j) { return alongY[static_cast<size_t>(i) * height + j]; }
  /// Vertex (i, j) lies inside a wall along x.
  bool vertexOnXWall(int i, int j) { return (i > 0 && xEdge(i - 1, j)) || (i < width && xEdge(i, j)); }
};

// Randomized depth-first search with an explicit stack (mazes of 10^6 cells would overflow the
// call stack). Neighbours are tried in a fixed order and one is drawn with SeededRandom::below.
MazeWalls carve(int width, int height, SeededRandom& random) {
  MazeWalls walls(width, height);
  std::vector<char> visited(static_cast<size_t>(width) * height, 0);
  auto cell = [&](int i, int j) { return static_cast<size_t>(j) * width + i; };
  std::vector<std::pair<int, int>> stack{{0, 0}};
  visited[0] = 1;
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    std::pair<int, int> options[4];
    uint32_t count = 0;
    if (i + 1 < width && !visited[cell(i + 1, j)]) options[count++] = {i + 1, j};
    if (i > 0 && !visited[cell(i - 1, j)]) options[count++] = {i - 1, j};
    if (j + 1 < height && !visited[cell(i, j + 1)]) options[count++] = {i, j + 1};
    if (j > 0 && !visited[cell(i, j - 1)]) options[count++] = {i, j - 1};
    if (count == 0) {
      stack.pop_back();
      continue;
    }
    const auto [ni, nj] = options[random.below(count)];
    if (ni != i) walls.yEdge(std::max(i, ni), j) = 0;  // the wall on line x = max(i, ni)
    else walls.xEdge(i, std::max(j, nj)) = 0;          // the wall on line y = max(j, nj)
    visited[cell(ni, nj)] = 1;
    stack.emplace_back(ni, nj);
  }
  return walls;
}

}  // namespace

Scene generateMaze(const MazeOptions& o) {
  if (o.width < 1 || o.height < 1 || !(o.cellSize > 0) || !(o.wallThickness > 0) ||
      !(o.wallThickness < 0.5 * o.cellSize) || !(o.wallHeight > kLightDrop) ||
      !(o.slabThickness > 0) || o.lights < 0 || !(o.lightEmission >= 0)) {
    throw std::invalid_argument("maze options: counts must be >= 1, sizes positive, walls "
                                "thinner than half a cell");
  }
  SeededRandom random(o.seed);
  MazeWalls walls = carve(o.width, o.height, random);

  Scene scene;
  const uint32_t wall = scene.addMaterial({"wall", {0.7, 0.68, 0.62}, {}});
  const uint32_t floor = scene.addMaterial({"floor", {0.5, 0.45, 0.4}, {}});
  const uint32_t ceiling = scene.addMaterial({"ceiling", {0.8, 0.8, 0.8}, {}});
  const uint32_t outside = scene.addMaterial({"outside", {0.5, 0.5, 0.5}, {}});
  const uint32_t light = scene.addMaterial(
      {"light", {0.8, 0.8, 0.8}, {o.lightEmission, o.lightEmission, o.lightEmission}});

  const double s = o.cellSize, half = 0.5 * o.wallThickness, h = o.wallHeight;
  const double sizeX = o.width * s, sizeY = o.height * s;
  Aabb extent;
  extent.add(Vec3{-half, -half, -o.slabThickness});
  extent.add(Vec3{sizeX + half, sizeY + half, h + o.slabThickness});
  SceneBuilder builder(scene, Tolerance::forBounds(extent));

  BoxMaterials slab = BoxMaterials::uniform(outside);
  slab.face[5] = floor;
  builder.addBox({-half, -half, -o.slabThickness}, {sizeX + half, sizeY + half, 0}, slab);
  slab = BoxMaterials::uniform(outside);
  slab.face[4] = ceiling;
  builder.addBox({-half, -half, h}, {sizeX + half, sizeY + half, h + o.slabThickness}, slab);

  // Walls along x: maximal runs, each including the vertex squares at its ends.
  for (int j = 0; j <= o.height; ++j) {
    for (int i = 0; i < o.width;) {
      if (!walls.xEdge(i, j)) {
        ++i;
        continue;
      }
      int end = i;
      while (end < o.width && walls.xEdge(end, j)) ++end;
      builder.addBox({i * s - half, j * s - half, 0}, {end * s + half, j * s + half, h}, wall);
      i = end;
    }
  }
  // Walls along y: runs broken at vertices that a wall along x already covers, and stopping
  // short of them, so that no two boxes overlap.
  for (int i = 0; i <= o.width; ++i) {
    for (int j = 0; j < o.height;) {
      if (!walls.yEdge(i, j)) {
        ++j;
        continue;
      }
      int end = j + 1;
      while (end < o.height && walls.yEdge(i, end) && !walls.vertexOnXWall(i, end)) ++end;
      const double y0 = j * s + (walls.vertexOnXWall(i, j) ? half : -half);
      const double y1 = end * s + (walls.vertexOnXWall(i, end) ? -half : half);
      builder.addBox({i * s - half, y0, 0}, {i * s + half, y1, h}, wall);
      j = end;
    }
  }

  // Lights in distinct random cells (a partial Fisher-Yates shuffle of the cell indices).
  const size_t cells = static_cast<size_t>(o.width) * o.height;
  const size_t lightCount =
      std::min(cells, o.lights > 0 ? static_cast<size_t>(o.lights) : std::max<size_t>(1, cells / 16));
  std::vector<uint32_t> order(cells);
  for (size_t k = 0; k < cells; ++k) order[k] = static_cast<uint32_t>(k);
  const double size = std::min(kLightSize, 0.5 * (s - o.wallThickness));
  for (size_t k = 0; k < lightCount; ++k) {
    const size_t pick = k + random.below(static_cast<uint32_t>(cells - k));
    std::swap(order[k], order[pick]);
    const double cx = (order[k] % static_cast<uint32_t>(o.width) + 0.5) * s;
    const double cy = (order[k] / static_cast<uint32_t>(o.width) + 0.5) * s;
    const double z = h - kLightDrop;
    builder.addAxisRect(2, false, {cx - size / 2, cy - size / 2, z}, {cx + size / 2, cy + size / 2, z},
                        light);
  }
  return scene;
}

}  // namespace gv
