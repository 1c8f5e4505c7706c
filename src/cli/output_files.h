// Where subcommands put their results: an output directory and the JSON files in it.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace gv::cli {

/// Creates the directory (and its parents) if missing; throws InputError naming it on failure.
std::filesystem::path makeOutputDirectory(const std::string& path);

/// Writes `value` pretty-printed to `path`; throws InputError naming it on failure.
void writeJsonFile(const nlohmann::json& value, const std::filesystem::path& path);

/// Writes `text` to `path` as is; throws InputError naming it on failure.
void writeTextFile(const std::string& text, const std::filesystem::path& path);

}  // namespace gv::cli
