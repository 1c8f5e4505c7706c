// Output directory and JSON files of the subcommands (see output_files.h).
#include "cli/output_files.h"

#include <fstream>

#include "util/input_error.h"

namespace gv::cli {

std::filesystem::path makeOutputDirectory(const std::string& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec) throw InputError(path, 0, "cannot create directory: " + ec.message());
  return path;
}

void writeJsonFile(const nlohmann::json& value, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << value.dump(2) << "\n";
  if (!out) throw InputError(path.string(), 0, "cannot write");
}

void writeTextFile(const std::string& text, const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw InputError(path.string(), 0, "cannot write");
}

}  // namespace gv::cli
