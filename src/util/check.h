// Always-on invariant checks (pbrt's CHECK): a broken invariant is a bug in globalvis, not bad
// input, so it stops the program at once with file:line instead of running on with wrong data.
// Unlike assert() they stay in Release builds. Bad input throws InputError (util/input_error.h).
// Keep conditions cheap: these run in optimized builds; never put one in an inner loop.
#pragma once

#include <fmt/core.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace gv::detail {

[[noreturn]] inline void checkFailed(const char* file, int line, const char* condition,
                                     const std::string& message) {
  std::fflush(stdout);
  std::fprintf(stderr, "%s:%d: CHECK failed: %s%s%s\n", file, line, condition,
               message.empty() ? "" : ": ", message.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace gv::detail

/// CHECK(cond): aborts with file:line and the condition's text when `cond` is false.
#define CHECK(cond) \
  ((cond) ? static_cast<void>(0) : ::gv::detail::checkFailed(__FILE__, __LINE__, #cond, {}))

/// CHECK_MSG(cond, "format {}", args...): the same with a fmt-formatted message (evaluated only
/// when the check fails).
#define CHECK_MSG(cond, ...)                                             \
  ((cond) ? static_cast<void>(0)                                         \
          : ::gv::detail::checkFailed(__FILE__, __LINE__, #cond, ::fmt::format(__VA_ARGS__)))
