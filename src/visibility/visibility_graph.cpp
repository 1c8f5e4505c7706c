// visibility.txt (the paper's §7.3 file format) and stats.json for a VisibilityGraph.
#include "visibility/visibility_graph.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "util/input_error.h"

namespace gv {

void SequenceHistogram::add(size_t length, bool success) {
  auto& v = success ? successes : failures;
  if (successes.size() <= length) successes.resize(length + 1, 0);
  if (failures.size() <= length) failures.resize(length + 1, 0);
  ++v[length];
}

SequenceHistogram& SequenceHistogram::operator+=(const SequenceHistogram& o) {
  successes.resize(std::max(successes.size(), o.successes.size()), 0);
  failures.resize(std::max(failures.size(), o.failures.size()), 0);
  for (size_t i = 0; i < o.successes.size(); ++i) successes[i] += o.successes[i];
  for (size_t i = 0; i < o.failures.size(); ++i) failures[i] += o.failures[i];
  return *this;
}

VisibilityTxtWriter::VisibilityTxtWriter(const std::string& path) : file_(path) {
  file_.append(
      "# globalvis visibility: S R n b1 ... bn (patch ids of patches.obj, 0-based, S < R)\n");
  file_.append("# n = 0: VISIBLE; n > 0: PARTIAL with its blockers; pairs not listed: INVISIBLE\n");
}

VisibilityTxtWriter::~VisibilityTxtWriter() = default;

namespace {

/// The decimal digits of v < 10^7 packed into a word, first digit in the lowest byte (so that
/// storing the word little-endian writes them in order), their count in the top byte.
uint64_t packDigits(uint64_t v) {
  char digits[7];
  int count = 0;
  do {
    digits[count++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0);
  uint64_t word = uint64_t(count) << 56;
  for (int i = 0; i < count; ++i)
    word |= uint64_t(static_cast<unsigned char>(digits[count - 1 - i])) << (8 * i);
  return word;
}

}  // namespace

void VisibilityTxtWriter::put(uint64_t v, char after) {
  static_assert(std::endian::native == std::endian::little, "packed digits are stored LSB first");
  // The file has hundreds of millions of ids on big scenes (a library call per number was 4 %
  // of a 100k-patch run, and formatting each by divisions about as much): the digits of the
  // ids below kPackedIds are made once, and each id is then one 8-byte store.
  if (v < kPackedIds) {
    if (v >= packed_.size()) {
      const size_t from = packed_.size();
      packed_.resize(std::min<uint64_t>(kPackedIds, std::max<uint64_t>(v + 1, 2 * from)));
      for (size_t k = from; k < packed_.size(); ++k) packed_[k] = packDigits(k);
    }
    const uint64_t word = packed_[v];
    const auto count = static_cast<size_t>(word >> 56);
    // All 8 bytes are stored (little-endian: the digits in order); `after` overwrites the byte
    // after the digits, and the rest lies beyond what is committed.
    char* out = file_.room(sizeof word + 1);
    std::memcpy(out, &word, sizeof word);
    out[count] = after;
    file_.commit(count + 1);
    return;
  }
  const fmt::format_int digits(v);
  char* out = file_.room(digits.size() + 1);
  std::memcpy(out, digits.data(), digits.size());
  out[digits.size()] = after;
  file_.commit(digits.size() + 1);
}

void VisibilityTxtWriter::add(uint32_t s, uint32_t r, std::span<const uint32_t> blockers) {
  put(s, ' ');
  put(r, ' ');
  put(blockers.size(), blockers.empty() ? '\n' : ' ');
  for (size_t k = 0; k < blockers.size(); ++k)
    put(blockers[k], k + 1 == blockers.size() ? '\n' : ' ');
}

void VisibilityTxtWriter::add(const BlockerLists& lists) {
  for (size_t k = 0; k < lists.size(); ++k) add(lists.s(k), lists.r(k), lists.blockers(k));
}

void VisibilityTxtWriter::close() {
  file_.close();
}

void writeVisibilityTxt(const VisibilityGraph& graph, const std::string& path) {
  VisibilityTxtWriter out(path);
  for (const Interaction& in : graph.interactions) out.add(in);
  out.close();
}

namespace {

nlohmann::json stabbingJson(const StabbingStats& s) {
  return {{"tests", s.tests},
          {"blocked_by_clipping", s.blockedByClipping},
          {"blocked_by_lp", s.blockedByLp},
          {"stabbed", s.stabbed},
          {"unresolved", s.unresolved},
          {"lp_solves", s.lpSolves},
          {"simplex_fallbacks", s.simplexFallbacks},
          {"lp_numerical_failures", s.lpNumericalFailures},
          {"degenerate_portals", s.degeneratePortals}};
}

}  // namespace

nlohmann::json visibilityStatsJson(const VisibilityStats& s) {
  const double pairs = double(s.patches) * double(s.patches > 0 ? s.patches - 1 : 0) / 2;
  const uint64_t listed = s.pairsVisible + s.pairsPartial;
  return {
      {"patches", s.patches},
      {"cells", s.cells},
      {"portals", s.portals},
      {"dead_cells", s.deadCells},
      {"dead_portals", s.deadPortals},
      {"cells_before_merge", s.cellsBeforeMerge},
      {"portals_before_merge", s.portalsBeforeMerge},
      {"portals_before_join", s.portalsBeforeJoin},
      {"patch_pairs", pairs},
      {"pairs_listed", listed},
      {"pairs_listed_percent", pairs > 0 ? 100.0 * double(listed) / pairs : 0.0},
      {"pairs_visible", s.pairsVisible},
      {"pairs_partial", s.pairsPartial},
      {"partial_percent_of_listed", listed ? 100.0 * double(s.pairsPartial) / double(listed) : 0.0},
      {"same_cell_shortcuts", s.sameCellShortcuts},
      {"pairs_hidden_by_one_blocker", s.pairsHiddenByOne},
      {"pairs_hidden_by_coplanar_blockers", s.pairsHiddenByWall},
      {"thin_wall_slivers", s.thinWallSlivers},
      {"beyond_air_slivers", s.beyondAirSlivers},
      {"beyond_air_fragments", s.beyondAirFragments},
      {"pieces_across_openings", s.acrossPortalPieces},
      {"pieces_across_thin_slabs", s.acrossThinSlabPieces},
      {"coplanar_graze_pairs", s.coplanarGrazePairs},
      {"cell_pairs_visible", s.cellPairsVisible},
      {"cell_searches_over_budget", s.cellSearchesOverBudget},
      {"patch_searches_over_budget", s.patchSearchesOverBudget},
      {"patch_budget", s.patchBudget},
      {"cell_stabbing_tests", s.cellStabbingTests},
      {"cell_target_tests", s.cellTargetTests},
      {"cell_over_budget_tests", s.cellOverBudgetTests},
      {"patch_stabbing_tests", s.patchStabbingTests},
      {"patch_facing_rule_tests", s.patchFacingRuleTests},
      {"mean_patches_seen_per_patch", s.meanPatchesSeen},
      {"unresolved_stabbing_tests", s.unresolvedStabbing},
      {"stabbing",
       {{"cell_level", stabbingJson(s.cellStabbing)},
        {"patch_level", stabbingJson(s.patchStabbing)}}},
      {"mean_sequence_length", s.meanSequenceLength},
      {"fig13_successes_by_length", s.cellHistogram.successes},
      {"fig13_failures_by_length", s.cellHistogram.failures},
      {"mean_blockers_per_partial", s.meanBlockersPerPartial},
      {"mean_shaft_cull_per_partial", s.meanShaftCullPerPartial},
      {"shaft_cull_sampled_pairs", s.shaftSamples},
      {"seconds",
       {{"total", s.seconds},
        {"cells", s.cellSeconds},
        {"patches", s.patchSeconds},
        {"blockers", s.blockerSeconds}}},
      {"threads", s.threads},
      {"paper",
       {{"patches", 403},
        {"pairs_listed", 4391},
        {"pairs_listed_percent", 5.4},
        {"partial_percent_of_listed", 64.1},
        {"cell_stabbing_tests", 10128},
        {"patch_stabbing_tests", 16055},
        {"mean_sequence_length", 5},
        {"mean_blockers_per_partial", 5},
        {"cpu_seconds", 300}}}};
}

VisibilityGraph readVisibilityTxt(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot be opened for reading");
  VisibilityGraph g;
  std::string line;
  for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    Interaction it;
    size_t count = 0;
    if (!(ss >> it.s >> it.r >> count) || it.s >= it.r)
      throw InputError(path, lineNo, "expected `S R n b1 ... bn` with S < R");
    it.blockers.resize(count);
    for (uint32_t& b : it.blockers)
      if (!(ss >> b)) throw InputError(path, lineNo, "fewer blockers than n");
    g.interactions.push_back(std::move(it));
  }
  return g;
}

}  // namespace gv
