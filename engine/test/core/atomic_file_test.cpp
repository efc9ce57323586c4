// Atomic writes: content lands in full, replaces the old file, leaves no
// temporary file behind, and failures name the path.
#include "bowg/core/atomic_file.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
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

// Appended, patched and read back while temporary; the old file stays until
// the commit, and an abandoned stream leaves it as it was.
TEST(AtomicFile, AStreamIsAppendedPatchedReadBackAndPublishedAtTheCommit) {
  const std::string d = dir();
  const std::string path = d + "/streamed.bin";
  writeFileAtomically(path, std::string("old"));
  {
    AtomicFileStream out(path);
    out.write("head????", 8);
    out.write("body", 4);
    EXPECT_EQ(out.size(), 12u);
    out.writeAt("1234", 4, 4);  // the length field, known at the end
    char back[12];
    out.readAt(back, 12, 0);
    EXPECT_EQ(std::string(back, 12), "head1234body");
    EXPECT_THROW(out.readAt(back, 4, 10), IoError);  // past the end
    EXPECT_EQ(readAll(path), "old");
    out.commit();
  }
  EXPECT_EQ(readAll(path), "head1234body");
  {
    AtomicFileStream abandoned(path);
    abandoned.write("half", 4);
  }
  EXPECT_EQ(readAll(path), "head1234body");
  EXPECT_EQ(countTemporaries(d), 0);
}

TEST(AtomicFile, TemporariesOfDeadWritersAreRemovedOthersKept) {
  const std::string d = dir() + "/stale";
  ASSERT_EQ(std::system(("rm -rf '" + d + "' && mkdir -p '" + d + "'").c_str()), 0);
  const auto touch = [&](const std::string& name) { std::ofstream(d + "/" + name) << "x"; };
  const std::string alive = std::to_string(static_cast<long>(::getpid()));
  // 999999999 is above any pid_max (2^22): no such process.
  touch(".tmp-999999999-0-db.bowgdb");           // a writer killed mid-save: removed
  touch(".tmp-" + alive + "-999999-db.bowgdb");  // this process writing it: kept
  touch(".tmp-999999999-0-other.bowgdb");        // another destination: kept
  touch(".tmp-x-0-db.bowgdb");                   // not our naming: kept
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

TEST(AtomicFile, StaleTemporariesOfAPathAreRemovedWithoutAWrite) {
  const std::string d = dir() + "/stale_of";
  ASSERT_EQ(std::system(("rm -rf '" + d + "' && mkdir -p '" + d + "'").c_str()), 0);
  const auto touch = [&](const std::string& name) { std::ofstream(d + "/" + name) << "x"; };
  const auto exists = [&](const std::string& name) {
    struct stat st;
    return ::lstat((d + "/" + name).c_str(), &st) == 0;
  };
  const std::string dead = ".tmp-999999999-";  // above any pid_max: no such process
  const std::string alive = ".tmp-" + std::to_string(static_cast<long>(::getpid())) + "-";
  touch(dead + "0-db.bowgdb");                            // a save killed mid-write: removed
  std::ofstream(d + "/" + dead + "1-db.bowgdb").close();  // killed before writing: removed
  touch(alive + "7-db.bowgdb");                           // a live writer's: kept
  touch(dead + "0-other.bowgdb");                         // another destination's: kept
  touch(".tmp-x-0-db.bowgdb");                            // not the writer's naming: kept
  ASSERT_EQ(::mkdir((d + "/" + dead + "2-db.bowgdb").c_str(), 0755), 0);   // a directory: kept
  ASSERT_EQ(::mkfifo((d + "/" + dead + "3-db.bowgdb").c_str(), 0644), 0);  // a FIFO: kept
  // A link of that name to a file of ours: neither it nor its target goes.
  touch("target");
  ASSERT_EQ(::symlink((d + "/target").c_str(), (d + "/" + dead + "4-db.bowgdb").c_str()), 0);
  // Another user's file (testable when the test may give a file away).
  touch(dead + "5-db.bowgdb");
  const bool foreign = ::chown((d + "/" + dead + "5-db.bowgdb").c_str(), 65534, 65534) == 0;
  if (!foreign) ::unlink((d + "/" + dead + "5-db.bowgdb").c_str());

  EXPECT_EQ(removeStaleTemporariesOf(d + "/db.bowgdb"), 2u);
  EXPECT_FALSE(exists(dead + "0-db.bowgdb"));
  EXPECT_FALSE(exists(dead + "1-db.bowgdb"));
  EXPECT_TRUE(exists(alive + "7-db.bowgdb"));
  EXPECT_TRUE(exists(dead + "0-other.bowgdb"));
  EXPECT_TRUE(exists(".tmp-x-0-db.bowgdb"));
  EXPECT_TRUE(exists(dead + "2-db.bowgdb"));
  EXPECT_TRUE(exists(dead + "3-db.bowgdb"));
  EXPECT_TRUE(exists(dead + "4-db.bowgdb"));
  EXPECT_TRUE(exists("target"));
  if (foreign) EXPECT_TRUE(exists(dead + "5-db.bowgdb"));
  // Nothing to do, and paths without a file name, are no error.
  EXPECT_EQ(removeStaleTemporariesOf(d + "/db.bowgdb"), 0u);
  EXPECT_EQ(removeStaleTemporariesOf(d + "/missing_dir/db.bowgdb"), 0u);
  EXPECT_EQ(removeStaleTemporariesOf(""), 0u);
  EXPECT_EQ(removeStaleTemporariesOf(d + "/"), 0u);
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
