// Tests of the Quake .map parser: both texture formats, comments, skipped patches, and bad input
// reported with its line.
#include "quake/map_file.h"

#include <gtest/gtest.h>

#include <cctype>
#include <optional>
#include <random>

#include "quake/map_to_scene.h"
#include "util/input_error.h"

namespace gv {
namespace {

size_t errorLine(const std::string& text) {
  try {
    parseMapText("bad.map", text);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.map");
    EXPECT_NE(std::string(e.what()).find("bad.map:"), std::string::npos) << e.what();
    return e.line();
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return 0;
}

TEST(MapFile, ReadsValveAndStandardSidesWithCommentsAndQuake2Fields) {
  const std::string text =
      "// Game: Quake\n"
      "// Format: Valve\n"
      "{\n"
      "\"classname\" \"worldspawn\"\n"
      "\"wad\"\t\"gfx/base.wad\" // trailing comment\n"
      "// brush 0\n"
      "{\n"
      "( -80 256 16 ) ( -80 257 16 ) ( -80 256 17 ) brown_brick [ 0 -1 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "( -64 64 16 ) ( -64 64 17 ) ( -63 64 16 ) {fence [ 1 0 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "( 1.5 2e1 -3 ) ( 0 0 0 ) ( 1 1 1 ) e1u1/metal2_1 0 0 0 1 1 134217728 1 10000\n"
      "( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) *water1 +16 -8 90 -1.000000 1.000000\n"
      "}\n"
      "{\n"
      "patchDef2\n{\nbase\n( 3 3 0 0 0 )\n(\n( ( 0 0 0 0 0 ) )\n)\n}\n"
      "}\n"
      "}\n"
      "{\n\"classname\" \"light\"\n\"origin\" \"0 0 64\"\n}\n";
  const MapFile map = parseMapText("t.map", text);
  ASSERT_EQ(map.entities.size(), 2u);
  const MapEntity& w = map.entities[0];
  EXPECT_EQ(w.className(), "worldspawn");
  EXPECT_EQ(w.line, 3u);
  ASSERT_NE(w.value("wad"), nullptr);
  EXPECT_EQ(*w.value("wad"), "gfx/base.wad");
  ASSERT_EQ(w.brushes.size(), 1u);
  const MapBrush& b = w.brushes[0];
  EXPECT_EQ(b.line, 7u);
  ASSERT_EQ(b.sides.size(), 4u);
  EXPECT_EQ(b.sides[0].texture, "brown_brick");
  EXPECT_EQ(b.sides[1].texture, "{fence");
  EXPECT_EQ(b.sides[2].texture, "e1u1/metal2_1");
  EXPECT_EQ(b.sides[3].texture, "*water1");
  EXPECT_EQ(b.sides[2].line, 10u);
  EXPECT_EQ(b.sides[2].points[0], (Vec3{1.5, 20, -3}));
  // Quake's rule on the first side: the plane x = -80 of a brush lying at x >= -80 faces -x.
  const Vec3 n = b.sides[0].outwardNormal();
  EXPECT_LT(n.x, 0);
  EXPECT_EQ(n.y, 0);
  EXPECT_EQ(n.z, 0);
  EXPECT_EQ(map.skippedPatches, 1u);
  ASSERT_EQ(map.warnings.size(), 1u);
  EXPECT_NE(map.warnings[0].find("patch"), std::string::npos);
  EXPECT_EQ(map.entities[1].className(), "light");
  EXPECT_TRUE(map.entities[1].brushes.empty());
}

TEST(MapFile, BrushPrimitivesAreSkippedAndCountedAndCrLfIsFine) {
  const std::string text =
      "{\r\n\"classname\" \"worldspawn\"\r\n{\r\nbrushDef\r\n{\r\n"
      "( 0 0 1 -64 ) ( ( 0.03 0 0 ) ( 0 0.03 0 ) ) tex 0 0 0\r\n}\r\n}\r\n"
      "{\r\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) tex 0 0 0 1 1\r\n}\r\n}\r\n";
  const MapFile map = parseMapText("p.map", text);
  EXPECT_EQ(map.skippedBrushPrimitives, 1u);
  ASSERT_EQ(map.entities.size(), 1u);
  ASSERT_EQ(map.entities[0].brushes.size(), 1u);
  EXPECT_EQ(map.entities[0].brushes[0].sides[0].line, 10u);
  EXPECT_EQ(*map.entities[0].value("classname"), "worldspawn");
}

TEST(MapFile, EmptyTextIsNoEntities) {
  EXPECT_TRUE(parseMapText("e.map", "// nothing\n\n").entities.empty());
}

TEST(MapFile, MalformedInputNamesTheLine) {
  const std::string side = "( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) tex 0 0 0 1 1\n";
  // A missing number: the texture fields run into the next line's '('.
  EXPECT_EQ(errorLine("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) tex 0 0 0 1\n" + side + "}\n}\n"), 4u);
  // Not a number.
  EXPECT_EQ(errorLine("{\n{\n" + side + "( 0 0 x ) ( 0 1 0 ) ( 1 0 0 ) tex 0 0 0 1 1\n}\n}\n"), 4u);
  // Non-finite.
  EXPECT_EQ(errorLine("{\n{\n( 0 0 inf ) ( 0 1 0 ) ( 1 0 0 ) tex 0 0 0 1 1\n}\n}\n"), 3u);
  // Unclosed entity: reported at the last line.
  EXPECT_EQ(errorLine("{\n\"classname\" \"worldspawn\"\n{\n" + side), 4u);
  // A key without a value.
  EXPECT_EQ(errorLine("{\n\"classname\"\n}\n"), 2u);
  // Unterminated string.
  EXPECT_EQ(errorLine("{\n\"classname\" \"world\n}\n"), 2u);
  // Stray token in an entity.
  EXPECT_EQ(errorLine("{\n\"a\" \"b\"\nbogus\n}\n"), 3u);
  // Extra junk after a side's fields.
  EXPECT_EQ(errorLine("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) tex 0 0 0 1 1 junk\n}\n}\n"), 3u);
  // Valve axis with a missing bracket.
  EXPECT_EQ(
      errorLine("{\n{\n( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 ) tex [ 1 0 0 0 [ 0 1 0 0 ] 0 1 1\n}\n}\n"), 3u);
  // A top-level token that is not '{'.
  EXPECT_EQ(errorLine("\n\n}\n"), 3u);
}

TEST(MapFile, MutatedMapsParseOrFailWithAnInputError) {
  // Seeded random damage to a valid map (a token dropped, replaced by junk, or the text cut
  // short): the parser and the conversion either read it or throw InputError; nothing else
  // escapes.
  const std::string good =
      "// Format: Valve\n{\n\"classname\" \"worldspawn\"\n{\n"
      "( -80 256 16 ) ( -80 257 16 ) ( -80 256 17 ) a [ 0 -1 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "( -64 64 16 ) ( -64 64 17 ) ( -63 64 16 ) a [ 1 0 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "( -64 256 16 ) ( -63 256 16 ) ( -64 257 16 ) a [ -1 0 0 0 ] [ 0 -1 0 0 ] 0 1 1\n"
      "( 64 384 96 ) ( 64 385 96 ) ( 65 384 96 ) a [ 1 0 0 0 ] [ 0 -1 0 0 ] 0 1 1\n"
      "( 64 80 48 ) ( 65 80 48 ) ( 64 80 49 ) a [ -1 0 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "( 64 384 48 ) ( 64 384 49 ) ( 64 385 48 ) a [ 0 1 0 0 ] [ 0 0 -1 32 ] 0 1 1\n"
      "}\n}\n{\n\"classname\" \"light\"\n\"origin\" \"0 0 64\"\n}\n";
  std::vector<size_t> starts;  // token starts
  for (size_t i = 0; i < good.size(); ++i)
    if (!std::isspace(static_cast<unsigned char>(good[i])) &&
        (i == 0 || std::isspace(static_cast<unsigned char>(good[i - 1]))))
      starts.push_back(i);
  const char* junk[] = {"{", "}", "(", ")", "[", "]", "\"", "nan", "1e999", "x", "//", "\"k\""};
  std::mt19937 rng(7);
  size_t errors = 0, parsed = 0, converted = 0;
  for (int round = 0; round < 2000; ++round) {
    std::string text = good;
    const size_t t = starts[rng() % starts.size()];
    size_t end = t;
    while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
    switch (rng() % 3) {
      case 0:
        text.erase(t, end - t);
        break;
      case 1:
        text.replace(t, end - t, junk[rng() % std::size(junk)]);
        break;
      default:
        text.resize(t);
        break;
    }
    std::optional<MapFile> map;
    try {
      map = parseMapText("m.map", text);
      ++parsed;
    } catch (const InputError& e) {
      ++errors;
      EXPECT_GE(e.line(), 1u) << text;  // parse errors always have a line
    }
    if (!map) continue;
    try {
      mapToScene(*map, "m.map");
      ++converted;
    } catch (const InputError&) {  // no visible face left, a bad light origin ...
    }
  }
  EXPECT_GT(errors, 500u);
  EXPECT_GT(parsed, 50u);
  EXPECT_GT(converted, 20u);
}

TEST(MapFile, MissingFileIsAnInputError) {
  EXPECT_THROW(readMapFile("/nonexistent/dir/none.map"), InputError);
}

}  // namespace
}  // namespace gv
