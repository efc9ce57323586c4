// LoopDetector::load of forged files: one field of a good file edited to a
// value no run can produce (a forged or buggy writer) and the checksum
// resealed, so that only the reader's own checks can catch it. Each is
// refused with a FormatError naming the file and the field, and the
// detector stays empty. Offsets from the layout (detector_file.cpp): header
// 28 bytes, u32 scoring, u32 entry count, then entry 0: stamp, centre x, y
// (f64), intrinsics valid (u8), fx, fy, cx, cy (f64), u32 feature count,
// feature 0: x, y, size, angle, response (f32), ...
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bowg/core/errors.h"
#include "core/resealed_checksum.h"
#include "detection/detector_file_runs.h"

namespace bowg {
namespace {

using testing::keyframes;
using testing::options;
using testing::outPath;
using testing::readBytes;
using testing::writeBytes;

constexpr std::size_t kEntries = 52;      // keyframes in the good file
constexpr std::size_t kNormalisers = 50;  // the normaliser history's length

/// Where the sections of the good file start, from the end: checksum 8, the
/// headings (u32 count, 3 f32 per entry), the missions (one unnamed: current u32, count u32, id
/// u32, name length u32, entry count u32, u32 per entry; detector_missions_test.cpp forges them),
/// the searchable flags (u32 count, a u8 per entry), the odometry positions (the
/// current run u32, u32 count, per entry u32 run and 3 f64), the place links
/// (u32 count, u32 per entry), the scale factors (u32 count, f32 per entry),
/// the hypothesis count 4 (none stored) and the two query odometers 16, the
/// odometers (u32 count, f64 per entry), the two missed-query counters 8, the
/// normaliser history (u32 count, 24 bytes each), the chain length (i32), its
/// island (32 bytes) and before it the previous scores.
struct TailLayout {
  explicit TailLayout(std::size_t file_size) {
    const std::size_t searchable = 4 + kEntries, positions = 4 + 4 + kEntries * (4 + 3 * 8);
    const std::size_t place_links = 4 + kEntries * 4, scale_factors = 4 + kEntries * 4;
    const std::size_t missions = 4 + 4 + 4 + 4 + 4 + kEntries * 4;
    headings = file_size - 8 - (4 + kEntries * 12);
    flags = headings - missions - searchable;
    run = flags - positions;
    links = run - place_links;
    scales = links - scale_factors;
    query_odometers = scales - (4 + 16);
    odometers = query_odometers - kEntries * 8;
    missed = odometers - 4 - 8;
    normalisers = missed - kNormalisers * 24;
    chain = normalisers - 4 - 4;
    island = chain - 32;
  }
  std::size_t headings, flags, run, links, scales, query_odometers, odometers, missed, normalisers,
      chain, island;
};

class ForgedDetectorFile : public ::testing::Test {
 protected:
  using Edits = std::vector<std::pair<std::size_t, std::string>>;

  void SetUp() override {
    auto kfs = keyframes();
    for (auto& kf : kfs) {
      kf.intrinsics.valid = true;
      kf.intrinsics.fx = kf.intrinsics.fy = 400.0;
      kf.intrinsics.cx = 320.0;
      kf.intrinsics.cy = 240.0;
    }
    voc_ = testing::vocabulary();
    LoopDetector a(voc_, options());
    for (std::size_t i = 0; i < kEntries; ++i) a.process(kfs[i]);
    path_ = outPath("forged_source.bowgdb");
    a.save(path_);
    good_ = readBytes(path_);
    ASSERT_EQ(good_[60], 1) << "entry 0's intrinsics-valid byte";
  }
  void TearDown() override { std::remove(path_.c_str()); }

  template <typename T>
  static std::string bytesOf(T value) {
    return std::string(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  template <typename T>
  T read(std::size_t at) const {
    T value;
    std::memcpy(&value, &good_[at], sizeof(T));
    return value;
  }

  /// Several edits (offset, bytes) at once, the checksum resealed: the load
  /// must fail naming the file and `why`, and leave the detector empty.
  void forgeAll(const std::string& name, const Edits& edits, const std::string& why) const {
    SCOPED_TRACE(name);
    std::string b = good_;
    for (const auto& e : edits) b.replace(e.first, e.second.size(), e.second);
    testing::resealChecksum(&b);
    const std::string forged = outPath(name);
    writeBytes(forged, b);
    LoopDetector c(voc_, options());
    try {
      c.load(forged);
      ADD_FAILURE() << "accepted";
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find(forged), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
    EXPECT_EQ(c.database().size(), 0u);
    std::remove(forged.c_str());
  }
  template <typename T>
  void forge(const std::string& name, std::size_t at, T value, const std::string& why) const {
    forgeAll(name, {{at, bytesOf(value)}}, why);
  }

  /// Entry 0's BoW vector follows its features: u32 count, then (u32 word,
  /// f64 weight) pairs.
  std::size_t bowOffset() const { return 97 + read<std::uint32_t>(93) * (6 * 4 + 32 + 4); }

  std::shared_ptr<const Vocabulary> voc_;
  std::string path_, good_;
  const double nan_ = std::nan(""), negative_ = -5.0;
};

TEST_F(ForgedDetectorFile, EntryFieldsAreRefusedByName) {
  // Entry 0: stamp at 36, fan centre at 44 and 52, intrinsics from 60, the
  // first keypoint from 97.
  forge("stamp.bowgdb", 36, -1e300, "entry 0 has an implausible stamp");
  forge("late.bowgdb", 36, 5e9, "entry 0 has an implausible stamp (5000000000");
  forge("stamp_nan.bowgdb", 36, nan_, "entry 0 has an implausible stamp (nan");
  forge("centre.bowgdb", 44, nan_, "entry 0 has a non-finite centre");
  forge("fx.bowgdb", 61, nan_, "entry 0 has invalid intrinsics");
  forge("fy.bowgdb", 69, negative_, "entry 0 has invalid intrinsics");
  forge("x.bowgdb", 97, std::nanf(""), "entry 0 keypoint 0 has a non-finite");
  forge("size.bowgdb", 105, -1.0f, "invalid size");
  forge("angle.bowgdb", 109, std::nanf(""), "entry 0 keypoint 0 has a non-finite");
}

TEST_F(ForgedDetectorFile, WeightsAreRefusedByName) {
  const std::size_t bow = bowOffset();
  const auto words = read<std::uint32_t>(bow);
  ASSERT_GT(words, 0u);
  for (const double w : {-5.0, 1e300, 0.0}) {
    forge("bow.bowgdb", bow + 4 + 4, w, "entry 0 has a BoW weight");
  }
  // A weight in range that is not the one the entry's words give (the
  // database rebuilds its vectors from the words: the file would contradict
  // itself): half the first weight.
  forge("bow_words.bowgdb", bow + 4 + 4, 0.5 * read<double>(bow + 4 + 4),
        "entry 0 has a BoW vector that is not the one its words give");
  // Entry 0's word groups follow its BoW vector: u32 count, (u32, f64) pairs.
  const std::size_t groups = bow + 4 + words * 12;
  ASSERT_GT(read<std::uint32_t>(groups), 0u);
  forge("group.bowgdb", groups + 4 + 4, negative_, "entry 0 has a word-group weight <= 0");
}

TEST_F(ForgedDetectorFile, PerEntrySectionsAreRefusedByName) {
  const TailLayout at(good_.size());
  forge("heading_count.bowgdb", at.headings, std::uint32_t{51},
        "odometry heading count differs from the entry count");
  // Entry 2's heading (unknown in the good file): x alone, then a known
  // vector of length 2.
  forge("heading_partial.bowgdb", at.headings + 4 + 12 * 2, 1.0f,
        "entry 2 has an odometry heading that is neither a unit vector nor all NaN");
  forge("heading_length.bowgdb", at.headings + 4 + 12 * 2, std::array<float, 3>{{2.f, 0.f, 0.f}},
        "entry 2 has an odometry heading that is neither a unit vector nor all NaN");
  forge("searchable_count.bowgdb", at.flags, std::uint32_t{51},
        "searchable flag count differs from the entry count");
  forge("searchable_flag.bowgdb", at.flags + 4 + 5, std::uint8_t{2},
        "entry 5 has searchable flag 2 (0 or 1)");
  forge("position_count.bowgdb", at.run + 4, std::uint32_t{51},
        "odometry position count differs from the entry count");
  forge("position_run.bowgdb", at.run + 8 + 28 * 2, std::uint32_t{1},
        "entry 2 belongs to odometry run 1, after the current run 0");
  forge("position_partial.bowgdb", at.run + 8 + 28 * 3 + 4 + 8, negative_,
        "entry 3 has an odometry position that is neither all finite nor all NaN");
  forge("link_count.bowgdb", at.links, std::uint32_t{51},
        "place link count differs from the entry count");
  forge("link_later.bowgdb", at.links + 4 + 4 * 3, std::uint32_t{7},
        "place link of entry 3 points to a later entry (7)");
  forge("scale_count.bowgdb", at.scales, std::uint32_t{51},
        "scale factor count differs from the entry count");
  forge("scale_negative.bowgdb", at.scales + 4 + 4, -1.2f,
        "entry 1 has a negative or non-finite pyramid scale factor");
  forge("scale_infinite.bowgdb", at.scales + 4, std::numeric_limits<float>::infinity(),
        "entry 0 has a negative or non-finite pyramid scale factor");
}

TEST_F(ForgedDetectorFile, OdometersAndNormalisersAreRefusedByName) {
  const TailLayout at(good_.size());
  forge("query_odometer.bowgdb", at.query_odometers, negative_,
        "a stored query odometer is invalid");
  forge("entry_odometer.bowgdb", at.odometers + 8, negative_,
        "entry 1 has a negative, non-finite or decreasing odometer");
  forge("missed.bowgdb", at.missed, std::int32_t{1000}, "missed-query count outside 0..52");
  forge("normaliser.bowgdb", at.normalisers, negative_,
        "a stored normaliser is negative or not finite");
  forge("normaliser_nan.bowgdb", at.normalisers + 16, nan_,
        "a stored normaliser is negative or not finite");
}

TEST_F(ForgedDetectorFile, ChainAndPreviousScoresAreRefusedByName) {
  const TailLayout at(good_.size());
  forge("chain.bowgdb", at.chain, std::int32_t{0x7fffffff},
        "chain length 2147483647 outside 0..52");
  // The chain's island (first, last, score, best entry, best score, size)
  // precedes its length; a chain that ends beyond the database:
  forgeAll("island.bowgdb",
           {{at.chain, bytesOf(std::int32_t{3})},
            {at.island, bytesOf(std::uint32_t{0})},
            {at.island + 4, bytesOf(std::uint32_t{1000})},
            {at.island + 16, bytesOf(std::uint32_t{0})}},
           "a temporal island lies outside the database");
  // The previous scores precede the island: u32 count k, then k (u32 entry,
  // f64 score) pairs. Find k from the layout, then point the last one past
  // the database, or make its score negative.
  std::size_t k = 0;
  while (k <= kEntries && read<std::uint32_t>(at.island - 12 * k - 4) != k) ++k;
  ASSERT_LE(k, kEntries) << "previous scores not found";
  ASSERT_GT(k, 0u);
  const std::size_t last_score = at.island - 12;
  forge("previous_entry.bowgdb", last_score, std::uint32_t{1000},
        "previous scores refer to an entry beyond the database");
  forge("previous_score.bowgdb", last_score + 4, negative_, "a previous score is negative");
}

}  // namespace
}  // namespace bowg
