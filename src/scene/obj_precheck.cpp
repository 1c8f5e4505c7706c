// OBJ / MTL prechecks with line numbers (see obj_precheck.h for why they exist).
#include "scene/obj_precheck.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "util/input_error.h"

namespace gv {
namespace {

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

/// Parses a whole token as a double; nullopt-like false when it is not a number at all.
bool parseDouble(std::string_view token, double& value) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);  // from_chars rejects '+'
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  // from_chars accepts "nan" and "inf" as numbers; the caller rejects them as non-finite.
  if (ec == std::errc::result_out_of_range) {
    value = INFINITY;
    return true;
  }
  return ec == std::errc() && ptr == end;
}

bool parseLong(std::string_view token, long& value) {
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

/// Calls fn(lineNumber, line) for each line, comment stripped. Lines end at "\n", "\r\n" or a lone
/// "\r", exactly as tinyobjloader splits them, so both readers see the same records.
template <typename Fn>
void forEachLine(const std::string& text, Fn&& fn) {
  size_t lineNo = 0, start = 0;
  while (start <= text.size()) {
    size_t end = text.find_first_of("\r\n", start);
    if (end == std::string::npos) end = text.size();
    ++lineNo;
    std::string_view line(text.data() + start, end - start);
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    fn(lineNo, line);
    if (end == text.size()) break;
    start = end + ((text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ? 2 : 1);
  }
}

std::string quoted(std::string_view s) { return "'" + std::string(s) + "'"; }

}  // namespace

ObjPrecheck precheckObj(const std::string& path, const std::string& text) {
  ObjPrecheck result;
  long vertexCount = 0;
  struct Pending { long index; size_t line; };
  std::vector<Pending> forward;  // positive indices beyond the vertices read so far
  forEachLine(text, [&](size_t lineNo, std::string_view line) {
    const auto tok = tokens(line);
    if (tok.empty()) return;
    if (tok[0] == "v") {
      if (tok.size() < 4)
        throw InputError(path, lineNo, "vertex needs 3 coordinates, found " + std::to_string(tok.size() - 1));
      Vec3 p;
      for (int k = 1; k < 4; ++k) {
        double& x = p[k - 1];
        if (!parseDouble(tok[k], x))
          throw InputError(path, lineNo, "vertex coordinate " + quoted(tok[k]) + " is not a number");
        if (!std::isfinite(x))
          throw InputError(path, lineNo, "vertex coordinate " + quoted(tok[k]) + " is not finite");
      }
      result.vertices.push_back(p);
      ++vertexCount;
    } else if (tok[0] == "f") {
      if (tok.size() < 4)
        throw InputError(path, lineNo, "face has " + std::to_string(tok.size() - 1) +
                                           " vertices; at least 3 are needed");
      for (size_t k = 1; k < tok.size(); ++k) {
        const std::string_view ref = tok[k].substr(0, tok[k].find('/'));
        long index = 0;
        if (!parseLong(ref, index))
          throw InputError(path, lineNo, "face vertex " + quoted(tok[k]) + " is not an index");
        if (index == 0) throw InputError(path, lineNo, "face vertex index 0 (OBJ indices start at 1)");
        if (index < 0 && vertexCount + index < 0)
          throw InputError(path, lineNo, "relative face vertex index " + std::to_string(index) +
                                             " reaches before the first vertex (" +
                                             std::to_string(vertexCount) + " defined so far)");
        if (index > vertexCount) forward.push_back({index, lineNo});
      }
    } else if (tok[0] == "mtllib") {
      for (size_t k = 1; k < tok.size(); ++k) result.libraries.push_back({std::string(tok[k]), lineNo});
    }
  });
  for (const Pending& p : forward)
    if (p.index > vertexCount)
      throw InputError(path, p.line, "face vertex index " + std::to_string(p.index) +
                                         " is out of range: the file has " +
                                         std::to_string(vertexCount) + " vertices");
  return result;
}

std::vector<std::string> precheckMtl(const std::string& path, const std::string& text) {
  std::vector<std::string> warnings;
  forEachLine(text, [&](size_t lineNo, std::string_view line) {
    const auto tok = tokens(line);
    if (tok.empty() || (tok[0] != "Kd" && tok[0] != "Ke")) return;
    if (tok.size() < 2)
      throw InputError(path, lineNo, std::string(tok[0]) + " needs an RGB value");
    if (tok[1] == "spectral" || tok[1] == "xyz")
      throw InputError(path, lineNo, std::string(tok[0]) + " " + std::string(tok[1]) +
                                         " is not supported; give RGB values");
    for (size_t k = 1; k < tok.size() && k < 4; ++k) {
      double x = 0;
      if (!parseDouble(tok[k], x))
        throw InputError(path, lineNo, std::string(tok[0]) + " value " + quoted(tok[k]) + " is not a number");
      if (!std::isfinite(x) || x < 0)
        throw InputError(path, lineNo, std::string(tok[0]) + " value " + quoted(tok[k]) +
                                           " must be finite and non-negative");
      if (tok[0] == "Kd" && x > 1)
        warnings.push_back(path + ":" + std::to_string(lineNo) + ": reflectance Kd " +
                           std::string(tok[k]) + " is above 1 (reflects more light than it gets)");
    }
  });
  return warnings;
}

}  // namespace gv
