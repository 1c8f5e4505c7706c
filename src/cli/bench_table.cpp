// The bench table, its JSON and the machine description.
#include "cli/bench_table.h"

#include <fmt/core.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <functional>
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
  const bool radiosity = std::any_of(
      rows.begin(), rows.end(), [](const BenchRow& r) { return r.radiositySeconds.has_value(); });
  auto hash = [](const std::string& h) { return h.empty() ? std::string("—") : "`" + h + "`"; };
  // Columns: heading, alignment, value.
  struct Column {
    const char* heading;
    const char* align;
    std::function<std::string(const BenchRow&)> value;
  };
  std::vector<Column> columns = {
      {"scene", "---", [](const BenchRow& r) { return r.name; }},
      {"patches", "--:", [](const BenchRow& r) { return countCell(uint64_t{r.patches}); }},
      {"load s", "--:", [](const BenchRow& r) { return cell(r.loadSeconds, "{:.3f}"); }},
      {"BSP s", "--:", [](const BenchRow& r) { return cell(r.bspSeconds, "{:.3f}"); }},
      {"portals s", "--:", [](const BenchRow& r) { return cell(r.portalSeconds, "{:.3f}"); }},
      {"vis s", "--:", [](const BenchRow& r) { return cell(r.visSeconds, "{:.2f}"); }},
      {"cells", "--:", [](const BenchRow& r) { return countCell(widen(r.cells)); }},
      {"portals", "--:", [](const BenchRow& r) { return countCell(widen(r.portals)); }},
      {"pairs listed", "--:", [](const BenchRow& r) { return countCell(r.pairsListed); }},
      {"VISIBLE", "--:", [](const BenchRow& r) { return countCell(r.pairsVisible); }},
      {"PARTIAL", "--:", [](const BenchRow& r) { return countCell(r.pairsPartial); }},
      {"mean blockers", "--:", [](const BenchRow& r) { return cell(r.meanBlockers, "{:.2f}"); }},
      {"excess", "--:",
       [](const BenchRow& r) {
         return cell(r.excess ? std::optional<double>(100 * *r.excess) : std::nullopt, "{:.1f} %");
       }},
      {"vis hash", "---", [&](const BenchRow& r) { return hash(r.visHash); }}};
  if (radiosity) {
    columns.push_back({"radiosity s", "--:", [](const BenchRow& r) {
                         return cell(r.radiositySeconds, "{:.2f}");
                       }});
    columns.push_back(
        {"links", "--:", [](const BenchRow& r) { return countCell(widen(r.radiosityLinks)); }});
    columns.push_back({"interactions", "--:", [](const BenchRow& r) {
                         return countCell(widen(r.radiosityInteractions));
                       }});
    columns.push_back(
        {"rays", "--:", [](const BenchRow& r) { return countCell(r.radiosityRays); }});
    columns.push_back({"radiosity peak MB", "--:", [](const BenchRow& r) {
                         return cell(r.radiosityPeakBytes
                                         ? std::optional<double>(*r.radiosityPeakBytes / 1e6)
                                         : std::nullopt,
                                     "{:.0f}");
                       }});
    columns.push_back(
        {"radiosity hash", "---", [&](const BenchRow& r) { return hash(r.radiosityHash); }});
  }
  const bool photons = std::any_of(rows.begin(), rows.end(),
                                   [](const BenchRow& r) { return r.photonL2.has_value(); });
  if (photons) {
    auto percent = [](const std::optional<double>& v, const char* format) {
      return cell(v ? std::optional<double>(100 * *v) : std::nullopt, format);
    };
    columns.push_back({"L2 of B−Ke vs photons (their noise alone)", "--:", [=](const BenchRow& r) {
                         std::string text = percent(r.photonL2, "{:.2f} %");
                         if (r.photonNoiseL2) text += percent(r.photonNoiseL2, " ({:.2f} %)");
                         return text;
                       }});
    columns.push_back(
        {"leaks", "--:", [](const BenchRow& r) { return countCell(widen(r.leaks)); }});
    columns.push_back({"worst region (of compared)", "--:", [=](const BenchRow& r) {
                         std::string text = percent(r.worstRegion, "{:+.1f} %");
                         if (r.regionsCompared && r.regionChannels)
                           text +=
                               fmt::format(" ({} of {})", *r.regionsCompared, *r.regionChannels);
                         return text;
                       }});
    columns.push_back(
        {"photons s", "--:", [](const BenchRow& r) { return cell(r.photonSeconds, "{:.1f}"); }});
  }
  columns.push_back(
      {"PVS s", "--:", [](const BenchRow& r) { return cell(r.pvsSeconds, "{:.2f}"); }});
  columns.push_back(
      {"PVS leafs", "--:", [](const BenchRow& r) { return countCell(widen(r.pvsLeafs)); }});
  columns.push_back(
      {"PVS mean leafs", "--:", [](const BenchRow& r) { return cell(r.pvsMeanLeafs, "{:.1f}"); }});
  columns.push_back({"PVS hash", "---", [&](const BenchRow& r) { return hash(r.pvsHash); }});
  columns.push_back({"checks", "---", [](const BenchRow& r) {
                       if (!r.failures.empty())
                         return fmt::format("**FAILED** ({})", r.failures.size());
                       return std::string(r.notes.empty() ? "ok" : "ok, partial");
                     }});

  std::string out = "|", rule = "|";
  for (const Column& c : columns) {
    out += fmt::format(" {} |", c.heading);
    rule += fmt::format("{}|", c.align);
  }
  out += "\n" + rule + "\n";
  for (const BenchRow& r : rows) {
    out += "|";
    for (const Column& c : columns) out += fmt::format(" {} |", c.value(r));
    out += "\n";
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
  return {
      {"scene", r.name},
      {"kind", r.kind},
      {"patches", r.patches},
      {"seconds",
       {{"load", orNull(r.loadSeconds)},
        {"bsp", orNull(r.bspSeconds)},
        {"portals", orNull(r.portalSeconds)},
        {"visibility", orNull(r.visSeconds)},
        {"radiosity", orNull(r.radiositySeconds)},
        {"pvs", orNull(r.pvsSeconds)},
        {"photons", orNull(r.photonSeconds)}}},
      {"cells", orNull(r.cells)},
      {"portals", orNull(r.portals)},
      {"pairs_listed", orNull(r.pairsListed)},
      {"pairs_visible", orNull(r.pairsVisible)},
      {"pairs_partial", orNull(r.pairsPartial)},
      {"mean_blockers_per_partial", orNull(r.meanBlockers)},
      {"excess", orNull(r.excess)},
      {"photon_l2_reflected", orNull(r.photonL2)},
      {"photon_l2_noise", orNull(r.photonNoiseL2)},
      {"photon_leak_surfaces", orNull(r.leaks)},
      {"photon_worst_region", orNull(r.worstRegion)},
      {"photon_regions_compared", orNull(r.regionsCompared)},
      {"photon_region_channels", orNull(r.regionChannels)},
      {"radiosity_links", orNull(r.radiosityLinks)},
      {"radiosity_interactions", orNull(r.radiosityInteractions)},
      {"radiosity_rays", orNull(r.radiosityRays)},
      {"radiosity_peak_resident_bytes", orNull(r.radiosityPeakBytes)},
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
