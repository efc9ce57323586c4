// Bounded file reading: regular files only, never blocking on a FIFO, the
// size limit checked before a byte is read, refusals that name the file, the
// limit and the variable that raises it.
#include "bowg/core/bounded_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>

#include "bowg/core/errors.h"

namespace bowg {
namespace {

std::string dir() {
  const std::string d = std::string(BOWG_TEST_OUTPUT_DIR) + "/bounded_file_test";
  const std::string cmd = "mkdir -p '" + d + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  return d;
}

// The refusal's message, or "" when the read succeeded.
std::string refusal(const std::string& path, FileKind kind) {
  try {
    readBoundedFile(path, kind);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

// Sets an environment variable for one test and restores it afterwards.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) { ::setenv(name, value, 1); }
  ~ScopedEnv() { ::unsetenv(name_); }

 private:
  const char* name_;
};

TEST(BoundedFile, ReadsARegularFileWhole) {
  const std::string path = dir() + "/plain.txt";
  std::ofstream(path, std::ios::binary) << std::string("a\0b", 3);
  EXPECT_EQ(readBoundedFile(path, FileKind::kText), std::string("a\0b", 3));
  BoundedFile f(path, FileKind::kText);
  EXPECT_EQ(f.size(), 3u);
  char head[2];
  f.readExactly(head, 2);
  EXPECT_EQ(std::string(head, 2), std::string("a\0", 2));
  EXPECT_EQ(f.readRest(), "b");
  char more[4];
  EXPECT_THROW(f.readExactly(more, 4), IoError);
}

// readAt: bytes at an offset, the current position left where it was, and
// a file shrunk since it was opened an error naming it.
TEST(BoundedFile, ReadsAtAnOffsetWithoutMovingAndRefusesBytesPastTheEnd) {
  const std::string path = dir() + "/read_at.bin";
  std::ofstream(path, std::ios::binary) << "0123456789";
  BoundedFile file(path, FileKind::kText);
  char two[2];
  file.readExactly(two, 2);
  char four[4];
  file.readAt(four, 4, 5);
  EXPECT_EQ(std::string(four, 4), "5678");
  file.readExactly(two, 2);  // the position is still 2
  EXPECT_EQ(std::string(two, 2), "23");
  ASSERT_EQ(::truncate(path.c_str(), 6), 0);
  try {
    file.readAt(four, 4, 5);
    FAIL() << "read past the end of a shrunk file";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ends before byte 9"), std::string::npos) << e.what();
  }
}

TEST(BoundedFile, RefusesAFifoWithoutBlocking) {
  const std::string path = dir() + "/pipe.bin";
  ::unlink(path.c_str());
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  const std::string why = refusal(path, FileKind::kVocabulary);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(why.find("FIFO"), std::string::npos) << why;
  EXPECT_NE(why.find(path), std::string::npos) << why;
  EXPECT_LT(seconds, 1.0);
}

TEST(BoundedFile, RefusesADirectoryAndADevice) {
  const std::string d = dir() + "/x.png";
  ASSERT_EQ(std::system(("mkdir -p '" + d + "'").c_str()), 0);
  EXPECT_NE(refusal(d, FileKind::kImage).find("is a directory"), std::string::npos);
  EXPECT_NE(refusal("/dev/zero", FileKind::kDatabase).find("device"), std::string::npos);
  EXPECT_NE(refusal(dir() + "/missing", FileKind::kText).find("No such file"), std::string::npos);
}

TEST(BoundedFile, RefusesAHugeSparseFileBeforeReadingIt) {
  const std::string path = dir() + "/sparse.bin";
  std::ofstream(path, std::ios::binary).put('x');
  ASSERT_EQ(::truncate(path.c_str(), 3ll << 30), 0);  // 3 GiB, no blocks on disk
  const std::string why = refusal(path, FileKind::kVocabulary);
  EXPECT_NE(why.find("vocabulary '" + path + "' is 3.0 GiB, more than the limit of 1.0 GiB"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("BOWG_MAX_VOCABULARY_MB"), std::string::npos) << why;
  ::unlink(path.c_str());
}

TEST(BoundedFile, TheEnvironmentVariableRaisesOrLowersTheLimit) {
  const std::string path = dir() + "/two_mib.bin";
  ASSERT_EQ(::truncate((std::ofstream(path), path).c_str(), 2 << 20), 0);
  {
    ScopedEnv env("BOWG_MAX_TEXT_MB", "1");
    EXPECT_EQ(fileLimit(FileKind::kText).max_bytes, 1u << 20);
    EXPECT_NE(refusal(path, FileKind::kText).find("is 2.0 MiB, more than the limit of 1.0 MiB"),
              std::string::npos);
  }
  {
    ScopedEnv env("BOWG_MAX_TEXT_MB", "2");
    EXPECT_EQ(refusal(path, FileKind::kText), "");
  }
  for (const char* bad : {"0", "-5", "1.5", "lots", "2000000000"}) {
    ScopedEnv env("BOWG_MAX_TEXT_MB", bad);
    EXPECT_THROW(fileLimit(FileKind::kText), InvalidParameter) << bad;
  }
}

TEST(BoundedFile, FormatsSizesAsAPersonReadsThem) {
  EXPECT_EQ(formatBytes(0), "0 bytes");
  EXPECT_EQ(formatBytes(1), "1 byte");
  EXPECT_EQ(formatBytes(1023), "1023 bytes");
  EXPECT_EQ(formatBytes(1536), "1.5 kB");
  EXPECT_EQ(formatBytes(300 * 1024), "300 kB");
  EXPECT_EQ(formatBytes(3ull << 30), "3.0 GiB");
  EXPECT_EQ(formatBytes(145ull * 1000 * 1000), "138 MiB");
}

}  // namespace
}  // namespace bowg
