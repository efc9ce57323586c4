// Atomic writes: content lands in full, replaces the old file, leaves no
// temporary file behind, and failures name the path.
#include "bowg/core/atomic_file.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "bowg/core/errors.h"

namespace bowg {
namespace {

std::string dir() {
  const std::string d = std::string(BOWG_TEST_OUTPUT_DIR) + "/atomic_file_test";
  std::string cmd = "mkdir -p '" + d + "'";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  return d;
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int countTemporaries(const std::string& d) {
  int n = 0;
  DIR* dp = ::opendir(d.c_str());
  if (dp == nullptr) return -1;
  while (dirent* e = ::readdir(dp)) {
    if (std::string(e->d_name).find(".tmp-") == 0) ++n;
  }
  ::closedir(dp);
  return n;
}

TEST(AtomicFile, WritesAndReplaces) {
  const std::string d = dir();
  const std::string path = d + "/a.bin";
  writeFileAtomically(path, std::string("first version"));
  EXPECT_EQ(readAll(path), "first version");
  const std::string binary("x\0y", 3);
  writeFileAtomically(path, binary);
  EXPECT_EQ(readAll(path), binary);
  writeFileAtomically(path, std::string());
  EXPECT_EQ(readAll(path), "");
  EXPECT_EQ(countTemporaries(d), 0);
}

TEST(AtomicFile, TemporaryPathKeepsTheNameAsSuffixInTheSameDirectory) {
  const std::string d = dir();
  AtomicFileWriter w(d + "/voc.yml.gz");
  const std::string t = w.tempPath();
  EXPECT_EQ(t.compare(0, d.size() + 1, d + "/"), 0) << t;
  EXPECT_EQ(t.substr(t.size() - 10), "voc.yml.gz");
  AtomicFileWriter plain("relative_name.txt");
  EXPECT_EQ(plain.tempPath().compare(0, 7, "./.tmp-"), 0) << plain.tempPath();
}

TEST(AtomicFile, UncommittedWriterRemovesItsTemporaryFile) {
  const std::string d = dir();
  std::string temp;
  {
    AtomicFileWriter w(d + "/never.txt");
    temp = w.tempPath();
    std::ofstream(temp) << "partial";
    EXPECT_EQ(countTemporaries(d), 1);
  }
  EXPECT_EQ(countTemporaries(d), 0);
  EXPECT_FALSE(std::ifstream(d + "/never.txt").good());
}

TEST(AtomicFile, CommitPublishesWhatWasWrittenToTheTemporaryPath) {
  const std::string d = dir();
  AtomicFileWriter w(d + "/committed.txt");
  std::ofstream(w.tempPath()) << "payload";
  w.commit();
  EXPECT_EQ(readAll(d + "/committed.txt"), "payload");
  EXPECT_EQ(countTemporaries(d), 0);
}

TEST(AtomicFile, TemporariesOfDeadWritersAreRemovedOthersKept) {
  const std::string d = dir() + "/stale";
  ASSERT_EQ(std::system(("rm -rf '" + d + "' && mkdir -p '" + d + "'").c_str()), 0);
  const auto touch = [&](const std::string& name) { std::ofstream(d + "/" + name) << "x"; };
  const std::string alive = std::to_string(static_cast<long>(::getpid()));
  // 999999999 is above any pid_max (2^22): no such process.
  touch(".tmp-999999999-0-db.bowgdb");  // a writer killed mid-save: removed
  touch(".tmp-" + alive + "-999999-db.bowgdb");  // this process writing it: kept
  touch(".tmp-999999999-0-other.bowgdb");   // another destination: kept
  touch(".tmp-x-0-db.bowgdb");              // not our naming: kept
  {
    AtomicFileWriter w(d + "/db.bowgdb");
    std::ofstream(w.tempPath()) << "new";
    w.commit();
  }
  EXPECT_EQ(readAll(d + "/db.bowgdb"), "new");
  EXPECT_FALSE(std::ifstream(d + "/.tmp-999999999-0-db.bowgdb").good());
  EXPECT_TRUE(std::ifstream(d + "/.tmp-" + alive + "-999999-db.bowgdb").good());
  EXPECT_TRUE(std::ifstream(d + "/.tmp-999999999-0-other.bowgdb").good());
  EXPECT_TRUE(std::ifstream(d + "/.tmp-x-0-db.bowgdb").good());
  EXPECT_EQ(countTemporaries(d), 3);
}

TEST(AtomicFile, FailuresNameThePath) {
  const std::string path = "/nonexistent_bowg_dir/sub/file.bin";
  try {
    writeFileAtomically(path, std::string("x"));
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(AtomicFileWriter(""), IoError);
  EXPECT_THROW(AtomicFileWriter(dir() + "/"), IoError);
  // Committing without having written the temporary file fails cleanly.
  AtomicFileWriter w(dir() + "/nothing.txt");
  EXPECT_THROW(w.commit(), IoError);
}

}  // namespace
}  // namespace bowg
