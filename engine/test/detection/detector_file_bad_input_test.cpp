// LoopDetector::load of bad files: clean FormatError/IoError on truncation,
// byte flips, another vocabulary, forged content, a missing file or a
// special one (FIFO, directory, device, huge sparse file), and the strong
// guarantee (a failed load keeps the old state).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bowg/core/errors.h"
#include "core/resealed_checksum.h"
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

// A file whose checksum is right but whose content no run can produce (a
// forged or buggy writer): refused by name, the detector untouched. Offsets
// from the layout (detector_file.cpp): header 28 bytes, u32 scoring, u32 entry
// count, then entry 0: stamp, centre x, y (f64), intrinsics valid (u8), fx,
// fy, cx, cy (f64), u32 feature count, feature 0: x, y, size, angle,
// response (f32), ...
TEST(DatabaseIo, ForgedContentIsRefusedByName) {
  const auto voc = vocabulary();
  auto kfs = keyframes();
  for (auto& kf : kfs) {
    kf.intrinsics.valid = true;
    kf.intrinsics.fx = kf.intrinsics.fy = 400.0;
    kf.intrinsics.cx = 320.0;
    kf.intrinsics.cy = 240.0;
  }
  LoopDetector a(voc, options());
  for (int i = 0; i < 52; ++i) a.process(kfs[i]);
  const std::string path = outPath("forged_source.bowgdb");
  a.save(path);
  const std::string good = readBytes(path);
  ASSERT_EQ(good[60], 1) << "entry 0's intrinsics-valid byte";
  // Several byte edits at once (offset, bytes), then the checksum resealed.
  using Edits = std::vector<std::pair<std::size_t, std::string>>;
  const auto forgeAll = [&](const std::string& name, const Edits& edits, const std::string& why) {
    SCOPED_TRACE(name);
    std::string b = good;
    for (const auto& e : edits) b.replace(e.first, e.second.size(), e.second);
    testing::resealChecksum(&b);
    const std::string forged = outPath(name);
    writeBytes(forged, b);
    LoopDetector c(voc, options());
    try {
      c.load(forged);
      ADD_FAILURE() << "accepted";
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find(forged), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
    EXPECT_EQ(c.database().size(), 0u);
    std::remove(forged.c_str());
  };
  const auto bytesOf = [](const void* value, std::size_t bytes) {
    return std::string(static_cast<const char*>(value), bytes);
  };
  const auto forge = [&](const std::string& name, std::size_t at, const void* value,
                         std::size_t bytes, const std::string& why) {
    forgeAll(name, {{at, bytesOf(value, bytes)}}, why);
  };
  const double nan = std::nan(""), negative = -5.0;
  const float fnan = std::nanf("");
  // Entry 0: stamp at 36, fan centre at 44 and 52, intrinsics from 60.
  const double minus_huge = -1e300, after_2106 = 5e9;
  forge("stamp.bowgdb", 36, &minus_huge, 8, "entry 0 has an implausible stamp");
  forge("late.bowgdb", 36, &after_2106, 8, "entry 0 has an implausible stamp (5000000000");
  forge("stamp_nan.bowgdb", 36, &nan, 8, "entry 0 has an implausible stamp (nan");
  forge("centre.bowgdb", 44, &nan, 8, "entry 0 has a non-finite centre");
  forge("fx.bowgdb", 61, &nan, 8, "entry 0 has invalid intrinsics");
  forge("fy.bowgdb", 69, &negative, 8, "entry 0 has invalid intrinsics");
  forge("x.bowgdb", 97, &fnan, 4, "entry 0 keypoint 0 has a non-finite");
  const float minus_one = -1.0f;
  forge("size.bowgdb", 105, &minus_one, 4, "invalid size");
  forge("angle.bowgdb", 109, &fnan, 4, "entry 0 keypoint 0 has a non-finite");
  // Entry 0's BoW vector follows its features: u32 count, then (u32 word,
  // f64 weight) pairs.
  std::uint32_t nf = 0;
  std::memcpy(&nf, &good[93], 4);
  const std::size_t bow = 97 + nf * (6 * 4 + 32 + 4);
  std::uint32_t words = 0;
  std::memcpy(&words, &good[bow], 4);
  ASSERT_GT(words, 0u);
  for (const double w : {-5.0, 1e300, 0.0}) {
    forge("bow.bowgdb", bow + 4 + 4, &w, 8, "entry 0 has a BoW weight");
  }
  // A weight in range that is not the one the entry's words give (the
  // database rebuilds its vectors from the words: the file would contradict
  // itself): half the first weight.
  double first = 0;
  std::memcpy(&first, &good[bow + 4 + 4], 8);
  const double half = 0.5 * first;
  forge("bow_words.bowgdb", bow + 4 + 4, &half, 8,
        "entry 0 has a BoW vector that is not the one its words give");
  // The chain length: before the normaliser history (u32 + 50 x 24), the
  // two missed-query counters (8), the odometers (u32 + 52 x 8), the two
  // query odometers (16), the hypothesis count (4), the scale factors (u32 +
  // 52 x 4), the place links, the odometry positions, the searchable flags
  // and the checksum (8).
  const std::size_t scale_factors = 4 + 52 * 4, place_links = 4 + 52 * 4;
  const std::size_t positions = 4 + 4 + 52 * (4 + 3 * 8), searchable = 4 + 52;
  const std::size_t chain =
      good.size() - (8 + searchable + positions + place_links + scale_factors + 4 + 16 + 4 +
                     52 * 8 + 8 + 4 + 50 * 24 + 4);
  const std::int32_t forever = 0x7fffffff;
  forge("chain.bowgdb", chain, &forever, 4, "chain length 2147483647 outside 0..52");
  // Entry 0's word groups follow its BoW vector: u32 count, (u32, f64) pairs.
  const std::size_t groups = bow + 4 + words * 12;
  std::uint32_t group_count = 0;
  std::memcpy(&group_count, &good[groups], 4);
  ASSERT_GT(group_count, 0u);
  forge("group.bowgdb", groups + 4 + 4, &negative, 8, "entry 0 has a word-group weight <= 0");
  // From the end: checksum 8, the searchable flags, the odometry positions (the current run u32,
  // then u32 count and per entry u32 run and 3 f64), the place links, the
  // scale factors, hypothesis count 4 (none stored), the two query
  // odometers 16, the odometers (u32 + 52 x 8), the missed-query counters
  // 8, the normalisers (u32 + 50 x 24).
  // The searchable flags (u32 count, a u8 per entry) close the payload.
  const std::size_t flags = good.size() - 8 - searchable;
  const std::uint32_t flag_count_short = 51;
  const std::uint8_t flag_two = 2;
  forge("searchable_count.bowgdb", flags, &flag_count_short, 4,
        "searchable flag count differs from the entry count");
  forge("searchable_flag.bowgdb", flags + 4 + 5, &flag_two, 1,
        "entry 5 has searchable flag 2 (0 or 1)");
  const std::size_t run = flags - positions;
  const std::uint32_t run_count_short = 51, later_run = 1;
  forge("position_count.bowgdb", run + 4, &run_count_short, 4,
        "odometry position count differs from the entry count");
  forge("position_run.bowgdb", run + 8 + 28 * 2, &later_run, 4,
        "entry 2 belongs to odometry run 1, after the current run 0");
  forge("position_partial.bowgdb", run + 8 + 28 * 3 + 4 + 8, &negative, 8,
        "entry 3 has an odometry position that is neither all finite nor all NaN");
  const std::size_t links = run - place_links;
  const std::uint32_t later = 7;
  const std::uint32_t fewer_links = 51;
  forge("link_count.bowgdb", links, &fewer_links, 4,
        "place link count differs from the entry count");
  forge("link_later.bowgdb", links + 4 + 4 * 3, &later, 4,
        "place link of entry 3 points to a later entry (7)");
  const std::size_t scales = links - scale_factors;
  const float negative_factor = -1.2f, infinite_factor = std::numeric_limits<float>::infinity();
  const std::uint32_t fewer = 51;
  forge("scale_count.bowgdb", scales, &fewer, 4, "scale factor count differs from the entry count");
  forge("scale_negative.bowgdb", scales + 4 + 4, &negative_factor, 4,
        "entry 1 has a negative or non-finite pyramid scale factor");
  forge("scale_infinite.bowgdb", scales + 4, &infinite_factor, 4,
        "entry 0 has a negative or non-finite pyramid scale factor");
  const std::size_t query_odometers = scales - (4 + 16);
  const std::size_t odometers = query_odometers - 52 * 8;
  const std::size_t missed = odometers - 4 - 8;
  const std::size_t normalisers = missed - 50 * 24;
  forge("query_odometer.bowgdb", query_odometers, &negative, 8,
        "a stored query odometer is invalid");
  forge("entry_odometer.bowgdb", odometers + 8, &negative, 8,
        "entry 1 has a negative, non-finite or decreasing odometer");
  const std::int32_t many = 1000;
  forge("missed.bowgdb", missed, &many, 4, "missed-query count outside 0..52");
  forge("normaliser.bowgdb", normalisers, &negative, 8, "a stored normaliser is negative or not finite");
  forge("normaliser_nan.bowgdb", normalisers + 16, &nan, 8,
        "a stored normaliser is negative or not finite");
  // The chain's island (32 bytes: first, last, score, best entry, best
  // score, size) precedes its length; a chain that ends beyond the database:
  const std::size_t island = chain - 32;
  const std::int32_t three = 3;
  const std::uint32_t beyond = 1000, zero = 0;
  forgeAll("island.bowgdb",
           {{chain, bytesOf(&three, 4)}, {island, bytesOf(&zero, 4)},
            {island + 4, bytesOf(&beyond, 4)}, {island + 16, bytesOf(&zero, 4)}},
           "a temporal island lies outside the database");
  // The previous scores precede the island: u32 count k, then k (u32 entry,
  // f64 score) pairs. Find k from the layout, then point the last one past
  // the database, or make its score negative.
  std::size_t k = 0;
  for (; k <= 52; ++k) {
    std::uint32_t stored = 0;
    std::memcpy(&stored, &good[island - 12 * k - 4], 4);
    if (stored == k) break;
  }
  ASSERT_LE(k, 52u) << "previous scores not found";
  ASSERT_GT(k, 0u);
  const std::size_t last_score = island - 12;
  forge("previous_entry.bowgdb", last_score, &beyond, 4,
        "previous scores refer to an entry beyond the database");
  forge("previous_score.bowgdb", last_score + 4, &negative, 8, "a previous score is negative");
  std::remove(path.c_str());
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
