// FNV-1a (64-bit) over values fed one by one: the result hashes `bench` prints, so that a faster
// run shows it computed the same answer.
#pragma once

#include <fmt/core.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>

namespace gv {

/// FNV-1a 64: offset basis and prime from the algorithm's definition (Fowler, Noll, Vo).
class Fnv1a {
 public:
  static constexpr uint64_t kOffsetBasis = 14695981039346656037ull;
  static constexpr uint64_t kPrime = 1099511628211ull;

  /// Feeds raw bytes.
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      hash_ ^= p[i];
      hash_ *= kPrime;
    }
  }
  /// Feeds an integer as its 8 little-endian bytes (so the hash does not depend on the type's
  /// width or the machine's byte order).
  template <class T, std::enable_if_t<std::is_integral_v<T>, int> = 0>
  void integer(T value) {
    uint64_t v = static_cast<uint64_t>(value);
    for (int i = 0; i < 8; ++i) {
      const unsigned char b = static_cast<unsigned char>(v >> (8 * i));
      bytes(&b, 1);
    }
  }
  void text(std::string_view s) { bytes(s.data(), s.size()); }
  uint64_t value() const { return hash_; }
  /// The hash as 16 hex digits.
  std::string hex() const { return fmt::format("{:016x}", hash_); }

 private:
  uint64_t hash_ = kOffsetBasis;
};

}  // namespace gv
