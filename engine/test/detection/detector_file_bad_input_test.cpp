// LoopDetector::load of bad files: clean FormatError/IoError on truncation,
// byte flips, another vocabulary, a missing file or a special one (FIFO,
// directory, device, huge sparse file), and the strong guarantee (a failed
// load keeps the old state); a flipped byte past the frame is reported as
// corruption. Forged content: detector_file_forged_test.cpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "core/special_files.h"
#include "detection/detector_file_runs.h"

namespace bowg {
namespace {

using testing::expectSameCandidates;
using testing::expectSameResult;
using testing::keyframes;
using testing::options;
using testing::outPath;
using testing::readBytes;
using testing::vocabulary;
using testing::writeBytes;

TEST(DatabaseIo, CorruptFilesGiveCleanErrorsAndKeepTheOldState) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetector saved(voc, options());
  for (int i = 0; i < 20; ++i) saved.process(kfs[i]);
  const std::string good = outPath("good.bowgdb");
  saved.save(good);
  const std::string bytes = readBytes(good);
  ASSERT_GT(bytes.size(), 1000u);

  // `victim` holds another state (30 keyframes); `twin` is its reference.
  LoopDetector victim(voc, options()), twin(voc, options());
  for (int i = 0; i < 30; ++i) {
    victim.process(kfs[i]);
    twin.process(kfs[i]);
  }
  const std::string bad = outPath("bad.bowgdb");
  int failures = 0;
  // Truncations: every offset in the header, then ~80 spread over the file.
  std::vector<std::size_t> cuts;
  for (std::size_t i = 0; i < 64; ++i) cuts.push_back(i);
  for (std::size_t i = 64; i < bytes.size(); i += bytes.size() / 80) cuts.push_back(i);
  cuts.push_back(bytes.size() - 1);
  for (std::size_t cut : cuts) {
    writeBytes(bad, bytes.substr(0, cut));
    EXPECT_THROW(victim.load(bad), FormatError) << "truncated at " << cut;
    ++failures;
  }
  // Byte flips over the whole file (header, payload, checksum).
  for (std::size_t at = 0; at < bytes.size(); at += bytes.size() / 97 + 1) {
    std::string flipped = bytes;
    flipped[at] = static_cast<char>(flipped[at] ^ 0x5a);
    writeBytes(bad, flipped);
    EXPECT_THROW(victim.load(bad), FormatError) << "flip at " << at;
    ++failures;
  }
  // Appended garbage.
  writeBytes(bad, bytes + "x");
  EXPECT_THROW(victim.load(bad), FormatError);
  EXPECT_THROW(victim.load(outPath("does_not_exist.bowgdb")), IoError);
  EXPECT_GT(failures, 100);

  // Strong guarantee: the victim still behaves exactly like its twin.
  EXPECT_EQ(victim.database().size(), 30u);
  for (std::size_t i = 30; i < 45; ++i) {
    expectSameResult(victim.process(kfs[i]), twin.process(kfs[i]));
    expectSameCandidates(victim, twin);
  }
  std::remove(good.c_str());
  std::remove(bad.c_str());
}

// A flip in the fingerprint, the payload or the stored sum is reported as
// what it is, the file's corruption, naming the file: not as another
// vocabulary or a content error, and not loaded (a flip in a descriptor
// would still decode). The victim keeps its state. Offsets: the
// fingerprint (12-19), then ~150 over the payload and the stored sum.
TEST(DatabaseIo, FlippedBytesPastTheFrameAreReportedAsCorruption) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetector saved(voc, options());
  for (int i = 0; i < 20; ++i) saved.process(kfs[i]);
  const std::string good = outPath("flips.bowgdb");
  saved.save(good);
  const std::string bytes = readBytes(good);
  LoopDetector victim(voc, options());
  for (int i = 0; i < 10; ++i) victim.process(kfs[i]);
  std::vector<std::size_t> offsets{12, 19, bytes.size() - 1};
  for (std::size_t at = 28; at < bytes.size(); at += bytes.size() / 150 + 1) offsets.push_back(at);
  const std::string bad = outPath("flipped.bowgdb");
  for (std::size_t at : offsets) {
    std::string flipped = bytes;
    flipped[at] = static_cast<char>(flipped[at] ^ 0x01);
    writeBytes(bad, flipped);
    try {
      victim.load(bad);
      ADD_FAILURE() << "loaded a file flipped at " << at;
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find(bad + "': checksum mismatch (the file is corrupt)"),
                std::string::npos)
          << "flip at " << at << ": " << e.what();
    }
  }
  EXPECT_EQ(victim.database().size(), 10u);
  victim.load(good);  // the same bytes unflipped
  EXPECT_EQ(victim.database().size(), 20u);
  std::remove(good.c_str());
  std::remove(bad.c_str());
}

TEST(DatabaseIo, AnotherVocabularyIsRejectedByName) {
  const auto kfs = keyframes();
  LoopDetector a(vocabulary(7), options());
  for (int i = 0; i < 5; ++i) a.process(kfs[i]);
  const std::string path = outPath("other_vocabulary.bowgdb");
  a.save(path);
  LoopDetector b(vocabulary(8), options());
  try {
    b.load(path);
    FAIL() << "loaded a database built with another vocabulary";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("vocabulary"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_EQ(b.database().size(), 0u);
  std::remove(path.c_str());
}

TEST(DatabaseIo, SaveToAnUnwritablePathThrowsIoError) {
  LoopDetector a(vocabulary(), options());
  EXPECT_THROW(a.save("/nonexistent_dir_bowg/x.bowgdb"), IoError);
}

TEST(DatabaseIo, SpecialFilesAreRefusedFastAndKeepTheOldState) {
  const auto kfs = keyframes();
  LoopDetector victim(vocabulary(), options()), twin(vocabulary(), options());
  for (int i = 0; i < 5; ++i) {
    victim.process(kfs[i]);
    twin.process(kfs[i]);
  }
  const auto load = [&](const std::string& path) { victim.load(path); };
  // 3 GiB is under the database limit: the header, read first, refuses it.
  const auto files = testing::makeSpecialFiles(std::string(BOWG_TEST_OUTPUT_DIR) + "/db_special",
                                               ".bowgdb", 3ull << 30, "bad magic");
  testing::expectSpecialFilesRefused(files, load);
  testing::expectRefusedFast(outPath("absent.bowgdb"), "No such file or directory", load);
  // A real header whose payload size does not match the file's length.
  victim.save(outPath("hole.bowgdb"));
  const std::string header = readBytes(outPath("hole.bowgdb")).substr(0, 28);
  writeBytes(outPath("hole.bowgdb"), header);
  ASSERT_EQ(::truncate(outPath("hole.bowgdb").c_str(), 900ll << 20), 0);
  testing::expectRefusedFast(outPath("hole.bowgdb"), "does not match the file length", load);
  // Over the limit, named with the variable that raises it.
  ::setenv("BOWG_MAX_DATABASE_MB", "100", 1);
  testing::expectRefusedFast(outPath("hole.bowgdb"),
                             "more than the limit of 100 MiB (raise it with the environment "
                             "variable BOWG_MAX_DATABASE_MB",
                             load);
  ::unsetenv("BOWG_MAX_DATABASE_MB");
  std::remove(outPath("hole.bowgdb").c_str());
  for (std::size_t i = 5; i < 8; ++i) {
    expectSameResult(victim.process(kfs[i]), twin.process(kfs[i]));
  }
}

}  // namespace
}  // namespace bowg
