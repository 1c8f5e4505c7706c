// Bad input (unreadable files, malformed records, absurd numbers): an error that names the file
// and line, which the CLI turns into a message and a non-zero exit. Bugs are CHECKs, not these.
#pragma once

#include <stdexcept>
#include <string>

namespace gv {

/// An error in user input. `line` is 1-based, or 0 when the error concerns the whole file.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, size_t line, const std::string& message)
      : std::runtime_error(format(file, line, message)), file_(std::move(file)), line_(line) {}

  const std::string& file() const { return file_; }
  size_t line() const { return line_; }

 private:
  static std::string format(const std::string& file, size_t line, const std::string& message) {
    return line > 0 ? file + ":" + std::to_string(line) + ": " + message : file + ": " + message;
  }
  std::string file_;
  size_t line_;
};

}  // namespace gv
