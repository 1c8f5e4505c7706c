// The bench table, its JSON and the machine description.
#include "cli/bench_table.h"

#include <fmt/core.h>

#include <ctime>
#include <fstream>
#include <thread>

namespace gv::cli {
namespace {

template <class T>
std::string cell(const std::optional<T>& v, const char* format) {
  return v ? fmt::format(fmt::runtime(format), *v) : std::string("—");
}

std::string countCell(const std::optional<uint64_t>& v) {
  if (!v) return "—";
  std::string digits = fmt::format("{}", *v), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::optional<uint64_t> widen(const std::optional<size_t>& v) {
  return v ? std::optional<uint64_t>(*v) : std::nullopt;
}

template <class T>
nlohmann::json orNull(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

}  // namespace

std::string MachineInfo::describe() const {
  return fmt::format("{}, {} hardware threads, {:.1f} GiB memory", cpu, threads, memoryGiB);
}

MachineInfo describeMachine() {
  MachineInfo m;
  m.threads = std::thread::hardware_concurrency();
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) m.cpu = line.substr(line.find_first_not_of(' ', colon + 1));
      break;
    }
  }
  std::ifstream meminfo("/proc/meminfo");
  for (std::string key; meminfo >> key;) {
    double kib = 0;
    meminfo >> kib;
    if (key == "MemTotal:") {
      m.memoryGiB = kib / (1024.0 * 1024.0);
      break;
    }
    meminfo.ignore(1 << 20, '\n');
  }
  return m;
}

std::string todayUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &tm);
  return buf;
}

std::string benchTableMarkdown(const std::vector<BenchRow>& rows) {
  std::string out =
      "| scene | patches | load s | BSP s | portals s | vis s | radiosity s | cells | portals | "
      "pairs listed | VISIBLE | PARTIAL | mean blockers | vis hash | PVS s | PVS leafs | "
      "PVS mean leafs | PVS hash | checks |\n"
      "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|---|--:|--:|--:|---|---|\n";
  for (const BenchRow& r : rows) {
    const std::string status =
        !r.failures.empty() ? fmt::format("**FAILED** ({})", r.failures.size())
                            : (r.notes.empty() ? "ok" : "ok, partial");
    out += fmt::format(
        "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} "
        "| {} |\n",
        r.name, countCell(std::optional<uint64_t>(r.patches)), cell(r.loadSeconds, "{:.2f}"),
        cell(r.bspSeconds, "{:.2f}"), cell(r.portalSeconds, "{:.2f}"), cell(r.visSeconds, "{:.2f}"),
        cell(r.radiositySeconds, "{:.2f}"), countCell(widen(r.cells)), countCell(widen(r.portals)),
        countCell(r.pairsListed), countCell(r.pairsVisible), countCell(r.pairsPartial),
        cell(r.meanBlockers, "{:.2f}"), r.visHash.empty() ? "—" : "`" + r.visHash + "`",
        cell(r.pvsSeconds, "{:.2f}"), countCell(widen(r.pvsLeafs)),
        cell(r.pvsMeanLeafs, "{:.1f}"), r.pvsHash.empty() ? "—" : "`" + r.pvsHash + "`", status);
  }
  std::string notes;
  for (const BenchRow& r : rows) {
    for (const std::string& f : r.failures) notes += fmt::format("- {}: FAILED {}\n", r.name, f);
    for (const std::string& n : r.notes) notes += fmt::format("- {}: {}\n", r.name, n);
  }
  if (!notes.empty()) out += "\n" + notes;
  return out;
}

nlohmann::json benchRowJson(const BenchRow& r) {
  return {{"scene", r.name},
          {"kind", r.kind},
          {"patches", r.patches},
          {"seconds",
           {{"load", orNull(r.loadSeconds)},
            {"bsp", orNull(r.bspSeconds)},
            {"portals", orNull(r.portalSeconds)},
            {"visibility", orNull(r.visSeconds)},
            {"radiosity", orNull(r.radiositySeconds)},
            {"pvs", orNull(r.pvsSeconds)}}},
          {"cells", orNull(r.cells)},
          {"portals", orNull(r.portals)},
          {"pairs_listed", orNull(r.pairsListed)},
          {"pairs_visible", orNull(r.pairsVisible)},
          {"pairs_partial", orNull(r.pairsPartial)},
          {"mean_blockers_per_partial", orNull(r.meanBlockers)},
          {"radiosity_links", orNull(r.radiosityLinks)},
          {"pvs_leafs", orNull(r.pvsLeafs)},
          {"pvs_mean_leafs_visible", orNull(r.pvsMeanLeafs)},
          {"visibility_hash", r.visHash.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.visHash)},
          {"radiosity_hash",
           r.radiosityHash.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.radiosityHash)},
          {"pvs_hash", r.pvsHash.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.pvsHash)},
          {"checks_passed", r.checks},
          {"failures", r.failures},
          {"notes", r.notes},
          {"ok", r.failures.empty()}};
}

}  // namespace gv::cli
