// BulkFile: what is written comes back byte for byte, whatever mix of room()/commit() and
// append() wrote it and wherever the buffer boundaries and the last partial block fall; it
// works where direct I/O is missing (tmpfs) and reports unwritable paths by name.
#include "util/bulk_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "support/temp_dir.h"
#include "util/input_error.h"

namespace gv {
namespace {

/// Writes `expected` (built here from a seeded generator) in pieces of random sizes, alternating
/// the two ways of writing; returns what was written.
std::string writeRandom(const std::filesystem::path& path, size_t bytes, uint32_t seed) {
  std::mt19937 rng(seed);
  std::string expected;
  BulkFile f(path.string());
  while (expected.size() < bytes) {
    const size_t n = std::uniform_int_distribution<size_t>(1, BulkFile::kMaxRoom)(rng);
    std::string piece(n, '\0');
    for (char& c : piece) c = static_cast<char>('a' + rng() % 26);
    if (rng() % 2) {
      std::copy(piece.begin(), piece.end(), f.room(n));
      f.commit(n);
    } else {
      f.append(piece);
    }
    expected += piece;
  }
  f.append(std::string(3 * BulkFile::kBufferBytes / 2, 'z'));  // longer than the buffer at once
  expected += std::string(3 * BulkFile::kBufferBytes / 2, 'z');
  f.close();
  f.close();  // idempotent
  return expected;
}

TEST(BulkFile, WritesBackByteForByteAcrossBuffersAndAPartialLastBlock) {
  const auto dir = test::scratchDir();
  // Several buffers' worth, ending mid-block (the tail is written without direct I/O).
  const std::string expected = writeRandom(dir / "big.txt", 2 * BulkFile::kBufferBytes + 12345, 1);
  ASSERT_NE(expected.size() % BulkFile::kBlock, 0u);
  EXPECT_EQ(test::readFile(dir / "big.txt"), expected);
}

TEST(BulkFile, SmallAndEmptyFiles) {
  const auto dir = test::scratchDir();
  {
    BulkFile f((dir / "empty.txt").string());
    f.close();
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "empty.txt"));
  EXPECT_EQ(std::filesystem::file_size(dir / "empty.txt"), 0u);
  {
    BulkFile f((dir / "one.txt").string());
    f.append("x\n");
    f.close();
  }
  EXPECT_EQ(test::readFile(dir / "one.txt"), "x\n");
}

TEST(BulkFile, WorksOnAFileSystemWithoutDirectIo) {
  // tmpfs refuses O_DIRECT at open: the plain-write path.
  if (!std::filesystem::is_directory("/dev/shm")) GTEST_SKIP() << "no /dev/shm here";
  const std::filesystem::path path = "/dev/shm/globalvis-bulk-file-test.txt";
  const std::string expected = writeRandom(path, BulkFile::kBufferBytes + 777, 2);
  EXPECT_EQ(test::readFile(path), expected);
  std::filesystem::remove(path);
}

TEST(BulkFile, AnUnwritablePathIsAnInputErrorNamingIt) {
  const auto dir = test::scratchDir();
  const std::string path = (dir / "no-such-dir" / "visibility.txt").string();
  try {
    BulkFile f(path);
    FAIL() << "opened " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos);
  }
}

}  // namespace
}  // namespace gv
