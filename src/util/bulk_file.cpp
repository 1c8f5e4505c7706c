// Direct (page-cache bypassing) writes of large files, with a plain-write fallback (bulk_file.h).
#include "util/bulk_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <new>

#include "util/input_error.h"

namespace gv {

BulkFile::BulkFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_DIRECT, 0666);
  direct_ = fd_ >= 0;
  if (fd_ < 0 && errno == EINVAL)  // the file system has no direct I/O
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) fail("cannot write");
  buffer_ = static_cast<char*>(std::aligned_alloc(kBlock, kBufferBytes));
  if (!buffer_) {
    ::close(fd_);
    throw std::bad_alloc();
  }
}

BulkFile::~BulkFile() {
  if (fd_ >= 0) ::close(fd_);
  std::free(buffer_);
}

void BulkFile::fail(const char* what) const {
  throw InputError(path_, 0, std::string(what) + ": " + std::strerror(errno));
}

void BulkFile::stopDirect() {
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags < 0 || ::fcntl(fd_, F_SETFL, flags & ~O_DIRECT) < 0) fail("cannot write");
  direct_ = false;
}

void BulkFile::writeAll(const char* data, size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd_, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      // Some file systems accept O_DIRECT at open but refuse the writes (alignment rules of
      // their own): go on through the page cache. Only whole blocks were written so far, so the
      // file offset is where the plain writes continue.
      if (errno == EINVAL && direct_) {
        stopDirect();
        continue;
      }
      fail("cannot write");
    }
    data += w;
    n -= static_cast<size_t>(w);
  }
}

void BulkFile::drain() {
  const size_t whole = direct_ ? size_ / kBlock * kBlock : size_;
  writeAll(buffer_, whole);
  // A direct write that fell back to plain writes in writeAll wrote `whole` all the same.
  std::memmove(buffer_, buffer_ + whole, size_ - whole);
  size_ -= whole;
}

void BulkFile::append(std::string_view bytes) {
  while (!bytes.empty()) {
    if (size_ == kBufferBytes) drain();
    const size_t n = std::min(bytes.size(), kBufferBytes - size_);
    std::memcpy(buffer_ + size_, bytes.data(), n);
    size_ += n;
    bytes.remove_prefix(n);
  }
}

void BulkFile::close() {
  if (fd_ < 0) return;
  drain();
  if (size_ > 0) {  // the tail, shorter than a block: direct writes cannot end the file there
    if (direct_) stopDirect();
    drain();
  }
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("cannot write");
}

}  // namespace gv
