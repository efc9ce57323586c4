// LoopDetector::save / load: identical behaviour after a round trip, clean
// FormatError/IoError on truncation, byte flips, another vocabulary or a
// missing file, and the strong guarantee (a failed load keeps the old state).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include "bowg/core/checksum.h"
#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

std::shared_ptr<const Vocabulary> vocabulary(std::uint64_t seed = 7) {
  return std::make_shared<Vocabulary>(testing::makeSyntheticVocabulary(10, 4, seed));
}

LoopDetectorOptions options() {
  LoopDetectorOptions o;
  o.geometric.direct_index_level = 2;
  o.islands.recent_exclusion = 10;
  o.distribution.enabled = true;
  o.similarity.lambda_1 = 0.4;
  o.similarity.lambda_2 = 0.4;
  return o;
}

std::string outPath(const std::string& name) {
  return std::string(BOWG_TEST_OUTPUT_DIR) + "/detector_file_test_" + name;
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Keyframes: forward over 40 m, then back over the first metres (revisits).
std::vector<KeyframeInput> keyframes() {
  const testing::Corridor c = testing::makeCorridor(50, 40, 31);
  std::mt19937_64 rng(8);
  std::vector<KeyframeInput> out;
  for (int i = 0; i < 40; ++i) out.push_back(testing::observeCorridor(c, i, 1.0 + i, rng, 2, 0.5));
  for (int i = 0; i < 25; ++i) {
    out.push_back(testing::observeCorridor(c, 39.5 - i, 41.0 + i, rng, 2, 0.5));
  }
  return out;
}

void expectSameResult(const LoopResult& a, const LoopResult& b) {
  EXPECT_EQ(a.query_id, b.query_id);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.match_id, b.match_id);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.best.entry, b.best.entry);
  EXPECT_DOUBLE_EQ(a.best.eta, b.best.eta);
  EXPECT_DOUBLE_EQ(a.word_normaliser, b.word_normaliser);
  EXPECT_DOUBLE_EQ(a.group_normaliser, b.group_normaliser);
}

void expectSameCandidates(const LoopDetector& a, const LoopDetector& b) {
  ASSERT_EQ(a.lastCandidates().size(), b.lastCandidates().size());
  for (std::size_t i = 0; i < a.lastCandidates().size(); ++i) {
    const CandidateScores &x = a.lastCandidates()[i], &y = b.lastCandidates()[i];
    EXPECT_EQ(x.entry, y.entry);
    EXPECT_DOUBLE_EQ(x.eta_w, y.eta_w);
    EXPECT_DOUBLE_EQ(x.eta_g, y.eta_g);
    EXPECT_DOUBLE_EQ(x.eta_d, y.eta_d);
    EXPECT_DOUBLE_EQ(x.eta, y.eta);
  }
}

TEST(DatabaseIo, RoundTripGivesIdenticalQueryResults) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetector a(voc, options());
  for (int i = 0; i < 52; ++i) a.process(kfs[i]);  // mid-revisit: chains are live
  const std::string path = outPath("roundtrip.bowgdb");
  a.save(path);
  LoopDetector b(voc, options());
  b.load(path);
  EXPECT_EQ(b.database().size(), 52u);
  EXPECT_EQ(b.database().groupTable().total(), a.database().groupTable().total());
  int loops = 0;
  for (std::size_t i = 52; i < kfs.size(); ++i) {
    const LoopResult ra = a.process(kfs[i]);
    const LoopResult rb = b.process(kfs[i]);
    expectSameResult(ra, rb);
    expectSameCandidates(a, b);
    if (ra.status == LoopStatus::kLoopDetected) ++loops;
  }
  EXPECT_GT(loops, 0) << "the scenario should exercise loops after the reload";
  std::remove(path.c_str());
}

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

TEST(DatabaseIo, EmptyDatabaseRoundTrips) {
  const auto voc = vocabulary();
  LoopDetector a(voc, options());
  const std::string path = outPath("empty.bowgdb");
  a.save(path);
  LoopDetector b(voc, options());
  b.process(keyframes()[0]);
  b.load(path);
  EXPECT_EQ(b.database().size(), 0u);
  std::remove(path.c_str());
}

// The normaliser history is part of the saved state: with the floor on, a
// reloaded detector divides by the same values as the one that kept running
// (a lost history would restart the median from nothing and change them).
TEST(DatabaseIo, NormaliserHistoryRoundTrips) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetectorOptions o = options();
  o.similarity.normaliser_floor = 1.5;  // binds for about half the queries
  o.similarity.normaliser_window = 9;
  LoopDetector a(voc, o);
  for (int i = 0; i < 45; ++i) a.process(kfs[i]);
  const std::string path = outPath("history.bowgdb");
  a.save(path);
  LoopDetector b(voc, o);
  b.load(path);
  int floored = 0;
  for (std::size_t i = 45; i < kfs.size(); ++i) {
    const LoopResult ra = a.process(kfs[i]);
    const LoopResult rb = b.process(kfs[i]);
    expectSameResult(ra, rb);
    EXPECT_DOUBLE_EQ(ra.word_divisor, rb.word_divisor);
    EXPECT_DOUBLE_EQ(ra.group_divisor, rb.group_divisor);
    expectSameCandidates(a, b);
    if (ra.word_divisor > ra.word_normaliser) ++floored;
  }
  EXPECT_GT(floored, 0) << "the scenario should exercise the floor after the reload";
  std::remove(path.c_str());
}

// A version-1 file (written before the normaliser history existed) still
// loads: the same file without the history, its version, payload size and
// checksum rewritten as version 1 wrote them. Without the floor it behaves
// exactly like the version-2 file.
TEST(DatabaseIo, OdometersAndMissedQueryCountersRoundTrip) {
  const auto voc = vocabulary();
  auto kfs = keyframes();
  // Odometer: metres driven (forward 0..39, then back), unknown for the
  // first five keyframes (odometry that started late).
  double driven = 0.0;
  for (std::size_t i = 0; i < kfs.size(); ++i) {
    if (i > 0) driven += i < 40 ? 1.0 : (i == 40 ? 0.5 : 1.0);
    if (i >= 5) kfs[i].odometer = driven;
  }
  LoopDetectorOptions o = options();
  o.islands.recent_exclusion_m = 8.0;
  o.temporal_score.alignment_window_m = 1.5;
  o.temporal_verification.max_island_distance_m = 2.0;
  o.temporal_score.max_missed_queries = 2;
  o.temporal_verification.max_missed_queries = 2;
  LoopDetector a(voc, o);
  for (int i = 0; i < 50; ++i) a.process(kfs[i]);
  const std::string path = outPath("odometer.bowgdb");
  a.save(path);
  LoopDetector b(voc, o);
  b.load(path);
  ASSERT_EQ(b.database().size(), 50u);
  for (std::size_t i = 0; i < 50; ++i) {
    const double x = a.database().entry(static_cast<EntryId>(i)).odometer;
    const double y = b.database().entry(static_cast<EntryId>(i)).odometer;
    if (i < 5) {
      EXPECT_TRUE(std::isnan(y)) << i;
    } else {
      EXPECT_EQ(x, y) << i;
    }
  }
  for (std::size_t i = 50; i < kfs.size(); ++i) {
    expectSameResult(a.process(kfs[i]), b.process(kfs[i]));
    expectSameCandidates(a, b);
  }
  std::remove(path.c_str());
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
  const auto forge = [&](const std::string& name, std::size_t at, const void* value,
                         std::size_t bytes, const std::string& why) {
    SCOPED_TRACE(name);
    std::string b = good;
    std::memcpy(&b[at], value, bytes);
    const std::uint64_t sum = checksum64(b.data(), b.size() - 8);
    for (int i = 0; i < 8; ++i) b[b.size() - 8 + i] = static_cast<char>((sum >> (8 * i)) & 0xff);
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
  const double nan = std::nan(""), negative = -5.0;
  const float fnan = std::nanf("");
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
  // The chain length: before the normaliser history (u32 + 50 x 24), the
  // two missed-query counters (8), the odometers (u32 + 52 x 8), the two
  // query odometers (16), the hypothesis count (4) and the checksum (8).
  const std::size_t chain = good.size() - (8 + 4 + 16 + 4 + 52 * 8 + 8 + 4 + 50 * 24 + 4);
  const std::int32_t forever = 0x7fffffff;
  forge("chain.bowgdb", chain, &forever, 4, "chain length 2147483647 outside 0..52");
  std::remove(path.c_str());
}

TEST(DatabaseIo, TemporalHypothesesRoundTrip) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetectorOptions one = options();
  one.islands.min_score = 0.05;  // several islands per query
  one.islands.max_intra_island_gap = 0;
  LoopDetectorOptions four = one;
  four.temporal_verification.hypotheses = 4;
  LoopDetector a(voc, four), single(voc, one);
  const std::string path = outPath("hypotheses.bowgdb");
  const std::string path_one = outPath("hypotheses_one.bowgdb");
  // Saved after the first query that followed other hypotheses: the file is
  // longer than the one-hypothesis file by a whole number of them (an
  // island and its chain length each), at most 3.
  const std::size_t per_hypothesis = 4 + 4 + 8 + 4 + 8 + 4 + 4;
  std::size_t saved_at = 0;
  for (std::size_t i = 0; i < kfs.size() && saved_at == 0; ++i) {
    a.process(kfs[i]);
    single.process(kfs[i]);
    a.save(path);
    single.save(path_one);
    const std::size_t extra = readBytes(path).size() - readBytes(path_one).size();
    EXPECT_EQ(extra % per_hypothesis, 0u);
    EXPECT_LE(extra / per_hypothesis, 3u);
    if (extra > 0) saved_at = i + 1;
  }
  ASSERT_GT(saved_at, 0u) << "no query followed more than one island";
  ASSERT_LT(saved_at, kfs.size());
  LoopDetector b(voc, four);
  b.load(path);
  for (std::size_t i = saved_at; i < kfs.size(); ++i) {
    expectSameResult(a.process(kfs[i]), b.process(kfs[i]));
    expectSameCandidates(a, b);
  }
  std::remove(path.c_str());
  std::remove(path_one.c_str());
}

TEST(DatabaseIo, VersionOneFilesLoadWithAnEmptyHistory) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetector a(voc, options());
  for (int i = 0; i < 45; ++i) a.process(kfs[i]);
  const std::string v2 = outPath("v2.bowgdb");
  a.save(v2);
  std::string bytes = readBytes(v2);
  // The history closes the version-2 payload: u32 count + count x 3 f64;
  // version 3 adds two i32 missed-query counters, the odometers (u32
  // count + 45 f64) and two query odometers (f64), version 4 the other
  // temporal hypotheses (u32 count, 0 with one hypothesis), then the u64
  // checksum. 44 keyframes had a previous one; the window is 50.
  const std::size_t history = 4 + 44 * 24 + 2 * 4 + 4 + 45 * 8 + 2 * 8 + 4;
  ASSERT_GT(bytes.size(), history + 8 + 28);
  bytes.resize(bytes.size() - 8 - history);
  auto putLe = [&bytes](std::size_t at, std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes[at + i] = static_cast<char>((v >> (8 * i)) & 0xff);
  };
  putLe(8, 1, 4);                   // version
  putLe(20, bytes.size() - 28, 8);  // payload size (header is 28 bytes)
  const std::uint64_t sum = checksum64(bytes.data(), bytes.size());
  bytes.resize(bytes.size() + 8);
  putLe(bytes.size() - 8, sum, 8);
  const std::string v1 = outPath("v1.bowgdb");
  writeBytes(v1, bytes);
  LoopDetector b(voc, options());
  b.load(v1);
  EXPECT_EQ(b.database().size(), 45u);
  for (std::size_t i = 45; i < kfs.size(); ++i) {
    expectSameResult(a.process(kfs[i]), b.process(kfs[i]));
    expectSameCandidates(a, b);
  }
  // Versions beyond the current one are refused by number.
  putLe(8, 5, 4);
  writeBytes(v1, bytes);
  try {
    b.load(v1);
    ADD_FAILURE() << "version 5 accepted";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("unsupported version 5"), std::string::npos) << e.what();
  }
  std::remove(v1.c_str());
  std::remove(v2.c_str());
}

}  // namespace
}  // namespace bowg
