// Reader of Quake PRT1/PRT2 portal files; every malformed record is an InputError with file:line.
#include "quake/prt_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>

#include "util/input_error.h"

namespace gv {
namespace {

// Counts above this are not a level, they are a corrupt file (and would exhaust memory).
constexpr long long kMaxCount = 50'000'000;
constexpr long long kMaxPortalPoints = 10'000;

class LineReader {
 public:
  LineReader(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  // Next non-blank line; false at end of file.
  bool next(std::string& line) {
    while (std::getline(in_, line)) {
      ++number_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") != std::string::npos) return true;
    }
    return false;
  }
  std::string nextRequired(const char* what) {
    std::string line;
    if (!next(line)) fail(std::string("unexpected end of file, expected ") + what);
    return line;
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(name_, number_, message);
  }
  size_t number() const { return number_; }

 private:
  std::istream& in_;
  std::string name_;
  size_t number_ = 0;
};

class Tokens {
 public:
  Tokens(std::string_view s, const LineReader& reader) : s_(s), reader_(reader) {}

  bool atEnd() {
    skipSpace();
    return pos_ >= s_.size();
  }
  long long integer(const char* what) {
    skipSpace();
    long long v = 0;
    const char* b = s_.data() + pos_;
    const char* e = s_.data() + s_.size();
    auto [p, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || (p < e && !isSeparator(*p)))
      reader_.fail(std::string("expected an integer (") + what + ")");
    pos_ += static_cast<size_t>(p - b);
    return v;
  }
  double real() {
    skipSpace();
    double v = 0;
    const char* b = s_.data() + pos_;
    const char* e = s_.data() + s_.size();
    auto [p, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || (p < e && !isSeparator(*p) && *p != ')'))
      reader_.fail("expected a number in a portal point");
    if (!std::isfinite(v)) reader_.fail("non-finite coordinate");
    pos_ += static_cast<size_t>(p - b);
    return v;
  }
  void expect(char c) {
    skipSpace();
    if (pos_ >= s_.size() || s_[pos_] != c) reader_.fail(std::string("expected '") + c + "'");
    ++pos_;
  }

 private:
  static bool isSeparator(char c) { return c == ' ' || c == '\t'; }
  void skipSpace() {
    while (pos_ < s_.size() && isSeparator(s_[pos_])) ++pos_;
  }
  std::string_view s_;
  const LineReader& reader_;
  size_t pos_ = 0;
};

long long countLine(LineReader& reader, const char* what) {
  const std::string line = reader.nextRequired(what);
  Tokens t(line, reader);
  const long long v = t.integer(what);
  if (!t.atEnd()) reader.fail(std::string("trailing text after ") + what);
  if (v < 0 || v > kMaxCount) reader.fail(std::string("implausible ") + what);
  return v;
}

}  // namespace

PrtFile parsePrt(std::istream& in, const std::string& name) {
  LineReader reader(in, name);
  PrtFile prt;
  std::string header = reader.nextRequired("the PRT1/PRT2 header");
  header.erase(header.find_last_not_of(" \t") + 1);
  header.erase(0, header.find_first_not_of(" \t"));
  if (header == "PRT1") {
    prt.version = 1;
  } else if (header == "PRT2") {
    prt.version = 2;
  } else {
    reader.fail("not a portal file: header is '" + header + "', expected PRT1 or PRT2");
  }
  prt.leafCount = static_cast<size_t>(countLine(reader, "leaf count"));
  prt.clusterCount = prt.version == 2 ? static_cast<size_t>(countLine(reader, "cluster count"))
                                      : prt.leafCount;
  const size_t portalCount = static_cast<size_t>(countLine(reader, "portal count"));
  if (prt.version == 2 && prt.clusterCount > prt.leafCount)
    reader.fail("more clusters than leafs");

  prt.portals.reserve(portalCount);
  for (size_t i = 0; i < portalCount; ++i) {
    const std::string line = reader.nextRequired("a portal line");
    Tokens t(line, reader);
    const long long points = t.integer("point count");
    if (points < 3 || points > kMaxPortalPoints)
      reader.fail("a portal needs 3 or more points, got " + std::to_string(points));
    const long long a = t.integer("first leaf"), b = t.integer("second leaf");
    const long long limit = static_cast<long long>(prt.clusterCount);
    const char* kind = prt.version == 2 ? "cluster" : "leaf";
    if (a < 0 || a >= limit || b < 0 || b >= limit)
      reader.fail(std::string(kind) + " index out of range 0.." + std::to_string(limit - 1) +
                  ": " + std::to_string(a) + " " + std::to_string(b));
    PrtPortal portal;
    portal.clusterA = static_cast<int>(a);
    portal.clusterB = static_cast<int>(b);
    portal.line = reader.number();
    portal.winding.reserve(static_cast<size_t>(points));
    for (long long k = 0; k < points; ++k) {
      t.expect('(');
      const double x = t.real(), y = t.real(), z = t.real();
      t.expect(')');
      portal.winding.push_back({x, y, z});
    }
    if (!t.atEnd()) reader.fail("more points than the count " + std::to_string(points));
    if (a == b) {
      ++prt.selfPortalsSkipped;  // leads nowhere: harmless, but no cell is entered through it
      continue;
    }
    prt.portals.push_back(std::move(portal));
  }

  prt.leafCluster.assign(prt.leafCount, -1);
  prt.clusterLeafs.assign(prt.clusterCount, {});
  if (prt.version == 1) {
    for (size_t l = 0; l < prt.leafCount; ++l) {
      prt.leafCluster[l] = static_cast<int>(l);
      prt.clusterLeafs[l] = {static_cast<int>(l)};
    }
  } else {
    // One list per cluster, ended by -1 (a list may wrap onto further lines).
    for (size_t c = 0; c < prt.clusterCount; ++c) {
      bool ended = false;
      while (!ended) {
        const std::string line = reader.nextRequired("a cluster's leaf list");
        Tokens t(line, reader);
        while (!t.atEnd()) {
          if (ended) reader.fail("text after the -1 that ends a cluster's leaf list");
          const long long leaf = t.integer("leaf index");
          if (leaf == -1) {
            ended = true;
            continue;
          }
          if (leaf < 0 || leaf >= static_cast<long long>(prt.leafCount))
            reader.fail("leaf index out of range 0.." + std::to_string(prt.leafCount - 1) + ": " +
                        std::to_string(leaf));
          int& owner = prt.leafCluster[static_cast<size_t>(leaf)];
          if (owner != -1)
            reader.fail("leaf " + std::to_string(leaf) + " is already in cluster " +
                        std::to_string(owner));
          owner = static_cast<int>(c);
          prt.clusterLeafs[c].push_back(static_cast<int>(leaf));
        }
      }
      std::sort(prt.clusterLeafs[c].begin(), prt.clusterLeafs[c].end());
    }
    for (size_t l = 0; l < prt.leafCount; ++l)
      if (prt.leafCluster[l] == -1)
        throw InputError(name, reader.number(), "leaf " + std::to_string(l) + " is in no cluster");
  }
  std::string extra;
  if (reader.next(extra)) reader.fail("unexpected text after the last record");
  return prt;
}

PrtFile readPrtFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open file");
  return parsePrt(in, path);
}

}  // namespace gv
