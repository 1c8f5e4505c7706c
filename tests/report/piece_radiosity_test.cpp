// Tests of radiosityOnPatches: radiosity of contact-split pieces gathered back onto the patches of
// an unsplit patch file, by hand-worked area-weighted means, and refusals of files that are not
// such a split.
#include "report/piece_radiosity.h"

#include <gtest/gtest.h>

#include "generators/scene_builder.h"
#include "scene/contact_split.h"

namespace gv {
namespace {

Scene twoPatches(bool split) {
  Scene scene;
  scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  SceneBuilder b(scene, Tolerance{10.0});
  if (split) {
    b.addAxisRect(2, true, {0, 0, 0}, {1.5, 1, 0}, 0);  // patch 0 in two pieces
    b.addAxisRect(2, true, {1.5, 0, 0}, {2, 1, 0}, 0);
  } else {
    b.addAxisRect(2, true, {0, 0, 0}, {2, 1, 0}, 0);
  }
  b.addAxisRect(0, true, {3, 0, 0}, {3, 1, 1}, 0);  // patch 1, whole
  return scene;
}

TEST(PieceRadiosity, AreaWeightedMeanOverEachPatchsPieces) {
  const auto r =
      radiosityOnPatches(twoPatches(false), twoPatches(true), {{1, 2, 3}, {3, 2, 1}, {5, 5, 5}});
  ASSERT_TRUE(r.has_value());
  ASSERT_EQ(r->size(), 2u);
  EXPECT_DOUBLE_EQ((*r)[0].r, (1.5 * 1 + 0.5 * 3) / 2);
  EXPECT_DOUBLE_EQ((*r)[0].g, 2.0);
  EXPECT_DOUBLE_EQ((*r)[0].b, (1.5 * 3 + 0.5 * 1) / 2);
  EXPECT_EQ((*r)[1], (Rgb{5, 5, 5}));
}

TEST(PieceRadiosity, AgreesWithTheContactSplitOfTheSameScene) {
  // A box on a floor: the floor's pieces are all given their index as radiosity; the floor's
  // mean is then the area-weighted mean of the indices, computed here from the pieces.
  Scene whole;
  whole.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  SceneBuilder b(whole, Tolerance{20.0});
  b.addAxisRect(2, true, {0, 0, 0}, {10, 10, 0}, 0);
  b.addBox({3, 4, 0}, {5, 7, 1}, 0);
  Scene pieces = whole;
  splitPatchesAtContacts(pieces);
  ASSERT_GT(pieces.patches.size(), whole.patches.size());
  std::vector<Rgb> b0;
  double sum = 0, area = 0;
  const size_t floorPieces = pieces.patches.size() - (whole.patches.size() - 1);
  for (size_t j = 0; j < pieces.patches.size(); ++j) {
    b0.push_back({double(j), 0, 0});
    if (j < floorPieces) {
      sum += j * pieces.patches[j].polygon.area();
      area += pieces.patches[j].polygon.area();
    }
  }
  const auto r = radiosityOnPatches(whole, pieces, b0);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR((*r)[0].r, sum / area, 1e-12);
  for (size_t p = 1; p < whole.patches.size(); ++p)
    EXPECT_EQ((*r)[p].r, double(floorPieces + p - 1));
}

TEST(PieceRadiosity, RefusesFilesThatAreNotASplit) {
  const Scene whole = twoPatches(false), split = twoPatches(true);
  // Wrong count of values.
  EXPECT_FALSE(radiosityOnPatches(whole, split, {{1, 1, 1}}).has_value());
  // Pieces out of order: patch 1 first.
  Scene shuffled = split;
  std::swap(shuffled.patches[0], shuffled.patches[2]);
  EXPECT_FALSE(radiosityOnPatches(whole, shuffled, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}).has_value());
  // A patch without pieces.
  Scene missing = split;
  missing.patches.pop_back();
  EXPECT_FALSE(radiosityOnPatches(whole, missing, {{1, 1, 1}, {1, 1, 1}}).has_value());
}

}  // namespace
}  // namespace gv
