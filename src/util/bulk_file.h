// An output file for gigabytes of text (visibility.txt on big scenes): written in large aligned
// blocks with O_DIRECT where the file system allows it. Through the page cache, writing 8.7 GB
// cost the 100k-patch office ~15 CPU seconds of kernel time (copying, dirty-page throttling,
// reclaim) on top of the ~105 s that produced it; direct writes cost almost none.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace gv {

class BulkFile {
 public:
  /// Alignment and granularity of direct writes: a multiple of every logical block size Linux
  /// file systems use.
  static constexpr size_t kBlock = 4096;
  /// Bytes buffered before a write (a multiple of kBlock).
  static constexpr size_t kBufferBytes = size_t{8} << 20;
  /// The most room() hands out at once.
  static constexpr size_t kMaxRoom = kBlock;

  /// Creates (or truncates) `path`. Throws InputError(path, 0, ...) when it cannot.
  explicit BulkFile(const std::string& path);
  /// Closes the file without the last write when close() was not called (an exception is on
  /// its way and the file is incomplete anyway).
  ~BulkFile();
  BulkFile(const BulkFile&) = delete;
  BulkFile& operator=(const BulkFile&) = delete;

  /// At least n <= kMaxRoom bytes to write into; commit() says how many were used.
  char* room(size_t n) {
    if (size_ + n > kBufferBytes) drain();
    return buffer_ + size_;
  }
  void commit(size_t n) { size_ += n; }
  void append(std::string_view bytes);
  /// Writes what is buffered and closes; throws InputError if any write failed. Idempotent.
  void close();
  /// Whether writes bypass the page cache (false on file systems without O_DIRECT, e.g. tmpfs,
  /// and after a direct write was refused).
  bool direct() const { return direct_; }

 private:
  /// Writes the buffer's whole blocks (everything when not direct) and keeps the rest.
  void drain();
  void writeAll(const char* data, size_t n);
  void stopDirect();
  [[noreturn]] void fail(const char* what) const;

  std::string path_;
  int fd_ = -1;
  bool direct_ = false;
  char* buffer_ = nullptr;
  size_t size_ = 0;
};

}  // namespace gv
