// `globalvis bench`: the pipeline over a size sweep of generated offices, the shared Quake maps
// and the shared OBJ levels (paper §7's measurements on this machine), every stage's result checked
// before its time counts; prints a table with a hash of each result and can refresh
// docs/BENCHMARKS.md.
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "cli/bench_run.h"
#include "cli/bench_table.h"
#include "cli/commands.h"
#include "cli/output_files.h"
#include "cli/scene_input.h"
#include "cli/thread_limit.h"
#include "generators/office.h"
#include "quake/map_to_scene.h"
#include "util/input_error.h"
#include "util/marked_section.h"

namespace gv::cli {
namespace {

/// The size sweep of generated offices (patch-count targets); --quick runs the first two.
constexpr size_t kOfficeSweep[] = {400, 1000, 3000, 10000};
constexpr size_t kQuickOffices = 2;

/// The maps run by default: small enough for the default budget (the others' visibility and
/// PVS take minutes); --all-maps runs every .map in the directory.
const char* const kDefaultMaps[] = {"qbspfeatures", "light_general", "E1M1-edited-ents"};
constexpr size_t kQuickMaps = 2;

/// The level run by --quick (the smallest of the shared set: a second of `vis`).
constexpr const char* kQuickLevel = "q3-oa_ctf2";
/// A level's lit variant: this prefix before its file name (../shared/data/levels/README.md).
constexpr const char* kLitPrefix = "lit-";

/// The markers of the section --update-docs rewrites.
constexpr const char* kDocsBegin = "<!-- bench:begin -->";
constexpr const char* kDocsEnd = "<!-- bench:end -->";

/// Whether `dir` is a directory; when it is not, a default one is skipped quietly and one the
/// user named is an input error ("not a directory of `what`").
bool directoryToRead(const std::string& dir, bool explicitDir, const char* what) {
  if (std::filesystem::is_directory(dir)) return true;
  if (explicitDir) throw InputError(dir, 0, std::string("not a directory of ") + what);
  return false;
}

std::vector<std::filesystem::path> mapsToRun(const std::string& dir, bool all, bool quick,
                                             bool explicitDir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> maps;
  if (!directoryToRead(dir, explicitDir, "Quake .map files")) return maps;
  if (all) {
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".map") maps.push_back(e.path());
    std::sort(maps.begin(), maps.end());
  } else {
    for (size_t i = 0; i < (quick ? kQuickMaps : std::size(kDefaultMaps)); ++i) {
      const fs::path p = fs::path(dir) / (std::string(kDefaultMaps[i]) + ".map");
      if (fs::exists(p)) maps.push_back(p);
    }
  }
  return maps;
}

/// The OBJ levels of `dir` to run: every .obj but the lit variants (a lit variant is the same
/// geometry with emitters; it joins its level's row for radiosity), sorted; --quick: one.
std::vector<std::filesystem::path> levelsToRun(const std::string& dir, bool quick,
                                               bool explicitDir) {
  namespace fs = std::filesystem;
  std::vector<fs::path> levels;
  if (!directoryToRead(dir, explicitDir, "OBJ levels")) return levels;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string stem = e.path().stem().string();
    if (e.path().extension() == ".obj" && stem.rfind(kLitPrefix, 0) != 0 &&
        (!quick || stem == kQuickLevel))
      levels.push_back(e.path());
  }
  std::sort(levels.begin(), levels.end());
  return levels;
}

std::string readWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

Action addBenchCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "bench",
      "Time the pipeline on a size sweep of generated offices, the shared Quake maps and the "
      "shared OBJ levels; "
      "check every result, print a table with result hashes, optionally refresh a "
      "markdown file's bench section. Exit code 1 when a check fails");
  struct State {
    bool quick = false, allMaps = false, noMaps = false, noOffices = false, noLevels = false,
         json = false;
    std::vector<size_t> officePatches;
    std::string maps = "../shared/data/quake", levels = "../shared/data/levels", updateDocs;
    BenchOptions options;
  };
  auto s = std::make_shared<State>();
  cmd->add_flag("--quick", s->quick,
                "Only the two smallest offices (~400 and ~1,000 patches), the two smallest "
                "maps (qbspfeatures, light_general) and the smallest level (q3-oa_ctf2)");
  auto* mapsOption =
      cmd->add_option("--maps", s->maps, "Directory of Quake .map files (with their .prt)")
          ->capture_default_str();
  cmd->add_flag("--all-maps", s->allMaps,
                "Every .map of the directory, not just the small ones (visibility and PVS of the "
                "big ones take minutes: raise --max-seconds)");
  auto* levelsOption =
      cmd->add_option("--levels", s->levels,
                      "Directory of OBJ levels: `vis` on each, and with --radiosity the "
                      "radiosity of its lit- variant against light tracing (--photons)")
          ->capture_default_str();
  cmd->add_flag("--no-maps", s->noMaps, "No Quake maps");
  cmd->add_flag("--no-offices", s->noOffices, "No generated offices");
  cmd->add_flag("--no-levels", s->noLevels, "No OBJ levels");
  cmd->add_option("--photons", s->options.photons,
                  "Photons of the light-tracing reference of each lit level (--radiosity)")
      ->capture_default_str()
      ->check(CLI::Range(uint64_t{1000}, uint64_t{1'000'000'000}));
  cmd->add_option("--office-patches", s->officePatches,
                  "Patch counts of the offices instead of the sweep 400 1000 3000 10000")
      ->check(CLI::Range(size_t{1}, size_t{10'000'000}));
  cmd->add_option("--max-seconds", s->options.maxSeconds,
                  "Budget per scene: a stage still running when it is spent is abandoned, later "
                  "stages skipped (the PVS has a budget of its own)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--min-coverage", s->options.minCoverage,
                  "BSP stop rule (see `globalvis cells --help`); by default `vis`'s choice, the "
                  "coarsest of its steps whose cells follow the scene")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--radiosity", s->options.radiosity,
                "Also solve radiosity as `radiosity` does by default (rays visibility, 16 rays per "
                "link, the default --quality, links culled by cells from 1000 patches on)");
  cmd->add_option("--threads", s->options.threads, "Worker threads (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--update-docs", s->updateDocs,
                  "Markdown file whose bench section (between <!-- bench:begin --> and "
                  "<!-- bench:end -->, appended if missing) gets the table, machine and date");
  cmd->add_flag("--json", s->json, "Print the results as JSON on stdout instead of the table");
  return [s, mapsOption, levelsOption] {
    const ThreadLimit threadLimit(s->options.threads);
    std::vector<BenchRow> rows;
    std::vector<size_t> sweep = s->officePatches;
    if (sweep.empty())
      sweep.assign(std::begin(kOfficeSweep),
                   std::begin(kOfficeSweep) + (s->quick ? kQuickOffices : std::size(kOfficeSweep)));
    if (s->noOffices) sweep.clear();
    for (const size_t target : sweep) {
      const OfficeOptions office = officeOptionsForPatchCount(target);
      const std::string name =
          fmt::format("office {}x{}x{}", office.floors, office.rows, office.columns);
      rows.push_back(benchScene(
          name, "office", [office] { return generateOffice(office); }, s->options));
      if (!s->json) fmt::print(stderr, "bench: {} done\n", name);
    }
    if (!s->noMaps) {
      for (const auto& map : mapsToRun(s->maps, s->allMaps, s->quick, mapsOption->count() > 0)) {
        const std::string path = map.string();
        BenchRow row = benchScene(
            map.stem().string(), "map", [path] { return importMap(path); }, s->options);
        std::filesystem::path prt = map;
        prt.replace_extension(".prt");
        if (std::filesystem::exists(prt)) benchPvs(prt.string(), s->options, row);
        rows.push_back(std::move(row));
        if (!s->json) fmt::print(stderr, "bench: {} done\n", map.stem().string());
      }
    }
    if (!s->noLevels) {
      for (const auto& level : levelsToRun(s->levels, s->quick, levelsOption->count() > 0)) {
        const std::string path = level.string();
        BenchOptions visOnly = s->options;
        visOnly.radiosity = false;  // the unlit geometry has no emitter: its lit variant's turn
        BenchRow row = benchScene(
            level.stem().string(), "level",
            [path] { return loadPipelineScene(path, SceneInputOptions{}); }, visOnly);
        const std::filesystem::path lit =
            level.parent_path() / (kLitPrefix + level.filename().string());
        if (s->options.radiosity && std::filesystem::exists(lit))
          benchLitLevel(lit.string(), s->options, row);
        rows.push_back(std::move(row));
        if (!s->json) fmt::print(stderr, "bench: {} done\n", level.stem().string());
      }
    }

    const MachineInfo machine = describeMachine();
    const std::string date = todayUtc();
    const std::string table = benchTableMarkdown(rows);
    const bool ok =
        std::all_of(rows.begin(), rows.end(), [](const BenchRow& r) { return r.failures.empty(); });
    if (s->json) {
      nlohmann::json j = {{"machine", machine.describe()},
                          {"date", date},
                          {"max_seconds_per_scene", s->options.maxSeconds},
                          {"ok", ok},
                          {"scenes", nlohmann::json::array()}};
      for (const BenchRow& r : rows) j["scenes"].push_back(benchRowJson(r));
      fmt::print("{}\n", j.dump(2));
    } else {
      fmt::print("{}\n", table);
      fmt::print("machine: {}; date {}\n", machine.describe(), date);
      fmt::print("{}\n", ok ? "OK: every check passed" : "FAILED: some checks failed");
    }
    if (!s->updateDocs.empty()) {
      const std::string body = fmt::format(
          "### `globalvis bench` table ({})\n\n"
          "Written by `make bench-scenes` (`globalvis bench{}{} --update-docs {}`); do not edit by "
          "hand. Machine: {} (shared with other jobs: times are indicative). Date {}. Budget {:g} "
          "s per scene. Every stage's result is checked before it is reported (cells fill the "
          "root box; visibility pairs well formed and `verifyVisibility` on {} rays and {} "
          "segments; PVS rows symmetric). The hashes (FNV-1a over the visibility interactions "
          "and over the PVS rows) show whether a change altered the answers.\n\n{}",
          s->quick ? "quick set" : (s->allMaps ? "all scenes" : "default set"),
          s->quick ? " --quick" : "", s->allMaps ? " --all-maps" : "", s->updateDocs,
          machine.describe(), date, s->options.maxSeconds, kBenchVerifyRays, kBenchVerifySegments,
          table);
      const std::string text =
          replaceMarkedSection(readWhole(s->updateDocs), kDocsBegin, kDocsEnd, body);
      writeTextFile(text, s->updateDocs);
    }
    return ok ? 0 : 1;
  };
}

}  // namespace gv::cli
