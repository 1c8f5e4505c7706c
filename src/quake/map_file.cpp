// Quake .map parsing: a whitespace tokenizer that keeps line numbers, then a recursive reader
// of entities, brushes and brush sides (standard and Valve 220 texture axes).
#include "quake/map_file.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>

#include "scene/read_file.h"
#include "util/input_error.h"

namespace gv {
namespace {

struct Token {
  std::string text;
  size_t line = 0;
  bool quoted = false;
};

/// Splits on whitespace; `"..."` is one token (no escapes, as in Quake); `//` starts a comment
/// running to the end of the line. Braces, parentheses and brackets are ordinary tokens: every
/// editor writes them apart, and texture names such as `{fence` must stay whole.
std::vector<Token> tokenize(const std::string& path, const std::string& text) {
  std::vector<Token> out;
  size_t line = 1;
  const size_t n = text.size();
  size_t i = 0;
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '/') {
      while (i < n && text[i] != '\n') ++i;
    } else if (c == '"') {
      const size_t start = ++i;
      while (i < n && text[i] != '"' && text[i] != '\n') ++i;
      if (i >= n || text[i] != '"') throw InputError(path, line, "unterminated quoted string");
      out.push_back({text.substr(start, i - start), line, true});
      ++i;
    } else {
      const size_t start = i;
      while (i < n && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      out.push_back({text.substr(start, i - start), line, false});
    }
  }
  return out;
}

class Reader {
 public:
  Reader(const std::string& path, std::vector<Token> tokens)
      : path_(path), tokens_(std::move(tokens)) {}

  MapFile readFile() {
    MapFile map;
    while (!atEnd()) map.entities.push_back(readEntity(map));
    if (map.skippedPatches > 0)
      map.warnings.push_back(path_ + ": skipped " + std::to_string(map.skippedPatches) +
                             " patch(es) (patchDef2/patchDef3): curved surfaces are not imported");
    if (map.skippedBrushPrimitives > 0)
      map.warnings.push_back(path_ + ": skipped " + std::to_string(map.skippedBrushPrimitives) +
                             " brush primitive(s) (brushDef/brushDef3): not a Quake 1 format");
    return map;
  }

 private:
  bool atEnd() const { return pos_ >= tokens_.size(); }
  size_t lastLine() const { return tokens_.empty() ? 1 : tokens_.back().line; }
  [[noreturn]] void fail(size_t line, const std::string& message) const {
    throw InputError(path_, line, message);
  }
  const Token& peek(const char* expecting) const {
    if (atEnd()) fail(lastLine(), std::string("unexpected end of file, expected ") + expecting);
    return tokens_[pos_];
  }
  const Token& next(const char* expecting) {
    const Token& t = peek(expecting);
    ++pos_;
    return t;
  }
  bool peekIs(const char* s) const {
    return !atEnd() && !tokens_[pos_].quoted && tokens_[pos_].text == s;
  }
  void expect(const char* s) {
    const Token& t = next(s);
    if (t.quoted || t.text != s)
      fail(t.line, std::string("expected '") + s + "', got '" + t.text + "'");
  }
  static std::optional<double> toNumber(const std::string& s) {
    double v = 0;
    const char* first = s.data();
    const char* last = s.data() + s.size();
    if (first != last && *first == '+') ++first;  // from_chars does not take a leading '+'
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || ptr != last) return std::nullopt;
    return v;
  }
  double number(const char* what) {
    const Token& t = next(what);
    const std::optional<double> v = t.quoted ? std::nullopt : toNumber(t.text);
    if (!v) fail(t.line, std::string("expected a number (") + what + "), got '" + t.text + "'");
    if (!std::isfinite(*v)) fail(t.line, std::string("non-finite number (") + what + ")");
    return *v;
  }
  Vec3 point() {
    expect("(");
    Vec3 p;
    p.x = number("point x");
    p.y = number("point y");
    p.z = number("point z");
    expect(")");
    return p;
  }

  MapEntity readEntity(MapFile& map) {
    const Token& open = next("'{'");
    if (open.quoted || open.text != "{")
      fail(open.line, "expected '{' to open an entity, got '" + open.text + "'");
    MapEntity e;
    e.line = open.line;
    for (;;) {
      const Token& t = peek("'}' closing the entity");
      if (t.quoted) {
        ++pos_;
        const Token& v = next("a value");
        if (!v.quoted) fail(t.line, "key \"" + t.text + "\" has no quoted value");
        if (v.line != t.line) fail(t.line, "key \"" + t.text + "\" has no value on its line");
        e.properties.emplace_back(t.text, v.text);
      } else if (t.text == "{") {
        ++pos_;
        readBrushInto(e, t.line, map);
      } else if (t.text == "}") {
        ++pos_;
        return e;
      } else {
        fail(t.line, "expected a \"key\" \"value\" pair, '{' or '}' in the entity opened on line " +
                         std::to_string(e.line) + ", got '" + t.text + "'");
      }
    }
  }

  /// Skips a balanced { ... } block whose opening brace is next.
  void skipBlock() {
    const Token& open = next("'{'");
    if (open.quoted || open.text != "{") fail(open.line, "expected '{', got '" + open.text + "'");
    int depth = 1;
    while (depth > 0) {
      const Token& t = next("'}'");
      if (t.quoted) continue;
      if (t.text == "{") ++depth;
      if (t.text == "}") --depth;
    }
  }

  void readBrushInto(MapEntity& e, size_t openLine, MapFile& map) {
    if (!atEnd() && !tokens_[pos_].quoted) {
      const std::string& kind = tokens_[pos_].text;
      const bool patch = kind == "patchDef2" || kind == "patchDef3";
      const bool primitive = kind == "brushDef" || kind == "brushDef3";
      if (patch || primitive) {
        ++pos_;
        skipBlock();
        expect("}");
        ++(patch ? map.skippedPatches : map.skippedBrushPrimitives);
        return;
      }
    }
    MapBrush b;
    b.line = openLine;
    while (!peekIs("}")) b.sides.push_back(readSide());
    ++pos_;
    e.brushes.push_back(std::move(b));
  }

  MapBrushSide readSide() {
    MapBrushSide s;
    const Token& first = peek("'(' or '}'");
    if (first.quoted || first.text != "(")
      fail(first.line,
           "expected '(' starting a brush side or '}' closing the brush, got '" + first.text + "'");
    s.line = first.line;
    for (Vec3& p : s.points) p = point();
    const Token& tex = next("a texture name");
    if (tex.text == "(" || tex.text == "}" || tex.text == "[")
      fail(tex.line, "expected a texture name, got '" + tex.text + "'");
    s.texture = tex.text;
    if (peekIs("[")) {  // Valve 220: [ ux uy uz uoff ] [ vx vy vz voff ] rot xscale yscale
      for (const char* axis : {"texture u axis", "texture v axis"}) {
        expect("[");
        for (int k = 0; k < 4; ++k) number(axis);
        expect("]");
      }
      for (const char* what : {"texture rotation", "texture x scale", "texture y scale"})
        number(what);
    } else {  // standard: xoff yoff rot xscale yscale
      for (const char* what : {"texture x offset", "texture y offset", "texture rotation",
                               "texture x scale", "texture y scale"})
        number(what);
    }
    // Optional Quake 2 / Hexen 2 surface fields on the same line.
    const size_t line = tokens_[pos_ - 1].line;
    for (int k = 0; k < 3 && !atEnd() && tokens_[pos_].line == line && !tokens_[pos_].quoted &&
                    toNumber(tokens_[pos_].text);
         ++k)
      ++pos_;
    if (!atEnd() && tokens_[pos_].line == line)
      fail(line, "unexpected '" + tokens_[pos_].text + "' after the brush side's texture fields");
    return s;
  }

  const std::string& path_;
  std::vector<Token> tokens_;
  size_t pos_ = 0;
};

}  // namespace

const std::string* MapEntity::value(const std::string& key) const {
  for (const auto& [k, v] : properties)
    if (k == key) return &v;
  return nullptr;
}

std::string MapEntity::className() const {
  const std::string* c = value("classname");
  return c ? *c : std::string();
}

MapFile parseMapText(const std::string& path, const std::string& text) {
  return Reader(path, tokenize(path, text)).readFile();
}

MapFile readMapFile(const std::string& path) {
  return parseMapText(path, readWholeFile(path));
}

}  // namespace gv
