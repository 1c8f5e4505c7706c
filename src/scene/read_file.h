// Reading a whole input file into memory, with the InputError messages every importer shares.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "util/input_error.h"

namespace gv {

/// The bytes of the file at `path`. Throws InputError (naming the file) when it is missing, a
/// directory, or unreadable.
inline std::string readWholeFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, 0, "file not found");
  if (fs::is_directory(path, ec)) throw InputError(path, 0, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot be opened for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path, 0, "read error");
  return ss.str();
}

}  // namespace gv
