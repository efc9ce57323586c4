// LoopDetector::save / load: identical behaviour after a round trip, for
// every part of the detector's memory, and files of the version before each
// part was saved. Packed positions and version-1 files:
// detector_file_versions_test.cpp; bad files: detector_file_bad_input_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "core/resealed_checksum.h"
#include "detection/detector_file_runs.h"
#include "detection/older_detector_files.h"

namespace bowg {
namespace {

using testing::asVersion;
using testing::expectSameCandidates;
using testing::expectSameResult;
using testing::fromVersion7Bytes;
using testing::keyframes;
using testing::options;
using testing::outPath;
using testing::putLe;
using testing::readBytes;
using testing::vocabulary;
using testing::writeBytes;

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

// The places joined by accepted loops come back (version 6): a detector
// saved again after loading writes the same bytes, links included, and a
// version-5 file (without them) loads with none.
TEST(DatabaseIo, PlaceLinksRoundTrip) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetectorOptions o = options();
  o.temporal_verification.linked_places = true;
  LoopDetector a(voc, o);
  int loops = 0;
  for (const KeyframeInput& kf : kfs) loops += a.process(kf).status == LoopStatus::kLoopDetected;
  ASSERT_GT(loops, 0);
  const std::string path = outPath("links.bowgdb"), again = outPath("links_again.bowgdb");
  a.save(path);
  const std::string bytes = readBytes(path);
  // The links close the version-6 payload: u32 count, then each entry's
  // parent.
  const std::size_t n = kfs.size();
  const std::size_t links = bytes.size() - 8 - fromVersion7Bytes(n) - 4 * n;
  std::size_t joined = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t parent = 0;
    std::memcpy(&parent, &bytes[links + 4 * i], 4);
    EXPECT_LE(parent, i);
    joined += parent != i;
  }
  EXPECT_GT(joined, 0u) << "accepted loops join places";
  LoopDetector b(voc, o);
  b.load(path);
  b.save(again);
  // The same bytes but the odometry run, which the load advanced (compared
  // whole: a mismatch would print ~100 kB).
  std::string expected = bytes;
  putLe(&expected, bytes.size() - 8 - fromVersion7Bytes(n), 1, 4);
  testing::resealChecksum(&expected);
  EXPECT_TRUE(readBytes(again) == expected);
  // Version 5: no links; saved again, every entry is its own place.
  writeBytes(path, asVersion(bytes, 4 + 4 * n + fromVersion7Bytes(n), 5));
  LoopDetector c(voc, o);
  c.load(path);
  c.save(again);
  const std::string unlinked = readBytes(again);
  ASSERT_EQ(unlinked.size(), bytes.size());
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t parent = 0;
    std::memcpy(&parent, &unlinked[links + 4 * i], 4);
    EXPECT_EQ(parent, i);
  }
  std::remove(path.c_str());
  std::remove(again.c_str());
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

// Odometers (unknown for the first keyframes) and the missed-query counters
// come back (version 3): the loaded detector answers as the original does.
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

// Which entries are in the inverse index comes back (version 8): a
// detector that leaves loop keyframes out of it, saved mid-revisit and
// loaded, answers the next keyframes as the original does; a version-7 file
// (without the flags) loads with every entry indexed.
TEST(DatabaseIo, SearchableFlagsRoundTrip) {
  const auto voc = vocabulary();
  const auto kfs = keyframes();
  LoopDetectorOptions o = options();
  o.islands.indexed_per_place = 1;
  LoopDetector a(voc, o);
  for (int i = 0; i < 52; ++i) a.process(kfs[i]);
  ASSERT_LT(a.database().searchableCount(), a.database().size()) << "loops before the save";
  const std::string path = outPath("searchable.bowgdb");
  a.save(path);
  const std::string bytes = readBytes(path);
  LoopDetector b(voc, o);
  b.load(path);
  ASSERT_EQ(b.database().size(), 52u);
  EXPECT_EQ(b.database().searchableCount(), a.database().searchableCount());
  for (EntryId i = 0; i < 52; ++i) {
    EXPECT_EQ(b.database().entry(i).searchable, a.database().entry(i).searchable) << i;
    EXPECT_EQ(b.database().rawGroups(i), a.database().rawGroups(i)) << i;
  }
  int loops = 0;
  for (std::size_t i = 52; i < kfs.size(); ++i) {
    const LoopResult ra = a.process(kfs[i]);
    expectSameResult(ra, b.process(kfs[i]));
    expectSameCandidates(a, b);
    loops += ra.status == LoopStatus::kLoopDetected;
  }
  EXPECT_GT(loops, 0);
  // The places' sizes came back with their links: the keyframes after the
  // load are indexed or not as in the original.
  ASSERT_EQ(b.database().size(), a.database().size());
  for (EntryId i = 52; i < a.database().size(); ++i) {
    EXPECT_EQ(b.database().entry(i).searchable, a.database().entry(i).searchable) << i;
  }
  writeBytes(path, asVersion(bytes, testing::fromVersion8Bytes(52), 7));
  LoopDetector c(voc, o);
  c.load(path);
  EXPECT_EQ(c.database().searchableCount(), 52u);
  std::remove(path.c_str());
}

// Odometry positions and their runs come back (version 7); the keyframes a
// loaded detector takes next belong to a new run (the restarted robot's
// odometry frame), and a version-6 file loads with unknown positions.
TEST(DatabaseIo, OdometryPositionsRoundTrip) {
  const auto voc = vocabulary();
  auto kfs = keyframes();
  // Forward along x 0..39, then back; no position for the first five
  // keyframes (odometry that started late).
  for (std::size_t i = 0; i < kfs.size(); ++i) {
    kfs[i].odometer = static_cast<double>(i);
    if (i < 5) continue;
    kfs[i].position.x = i < 40 ? static_cast<double>(i) : 79.0 - static_cast<double>(i);
    kfs[i].position.y = 0.25;
    kfs[i].position.z = -1.0;
  }
  LoopDetectorOptions o = options();
  o.islands.odometry_gate_m = 1.0;
  LoopDetector a(voc, o);
  for (int i = 0; i < 50; ++i) a.process(kfs[i]);
  const std::string path = outPath("positions.bowgdb"), again = outPath("positions_again.bowgdb");
  a.save(path);
  const std::string bytes = readBytes(path);
  LoopDetector b(voc, o);
  b.load(path);
  ASSERT_EQ(b.database().size(), 50u);
  for (EntryId i = 0; i < 50; ++i) {
    const DatabaseEntry& e = b.database().entry(i);
    EXPECT_EQ(e.odometry_run, 0u);
    if (i < 5) {
      EXPECT_TRUE(e.position.unknown()) << i;
    } else {
      EXPECT_EQ(e.position.x, kfs[i].position.x) << i;
      EXPECT_EQ(e.position.y, 0.25);
      EXPECT_EQ(e.position.z, -1.0);
    }
  }
  b.process(kfs[50]);
  EXPECT_EQ(b.database().entry(50).odometry_run, 1u);
  EXPECT_EQ(a.process(kfs[50]).query_id, 50u);
  EXPECT_EQ(a.database().entry(50).odometry_run, 0u);
  // Saved again, the file holds both runs; loaded, a third one starts.
  b.save(again);
  LoopDetector c(voc, o);
  c.load(again);
  EXPECT_EQ(c.database().entry(49).odometry_run, 0u);
  EXPECT_EQ(c.database().entry(50).odometry_run, 1u);
  c.process(kfs[51]);
  EXPECT_EQ(c.database().entry(51).odometry_run, 2u);
  // Version 6: no positions.
  writeBytes(path, asVersion(bytes, fromVersion7Bytes(50), 6));
  LoopDetector d(voc, o);
  d.load(path);
  for (const DatabaseEntry& e : d.database().entries()) EXPECT_TRUE(e.position.unknown());
  std::remove(path.c_str());
  std::remove(again.c_str());
}

// Odometry headings come back bit for bit (version 10), unknown ones
// unknown, and a version-9 file loads with every heading unknown.
TEST(DatabaseIo, OdometryHeadingsRoundTrip) {
  const auto voc = vocabulary();
  auto kfs = keyframes();
  // No heading for the first five keyframes, then turning a degree a
  // keyframe about z.
  for (std::size_t i = 0; i < kfs.size(); ++i) {
    kfs[i].odometer = static_cast<double>(i);
    if (i < 5) continue;
    kfs[i].heading.x = static_cast<float>(std::cos(i * M_PI / 180.0));
    kfs[i].heading.y = static_cast<float>(std::sin(i * M_PI / 180.0));
    kfs[i].heading.z = 0.f;
  }
  LoopDetectorOptions o = options();
  o.islands.heading_gate_deg = 30.0;
  LoopDetector a(voc, o);
  for (int i = 0; i < 50; ++i) a.process(kfs[i]);
  const std::string path = outPath("headings.bowgdb");
  a.save(path);
  const std::string bytes = readBytes(path);
  LoopDetector b(voc, o);
  b.load(path);
  ASSERT_EQ(b.database().size(), 50u);
  for (EntryId i = 0; i < 50; ++i) {
    const OdometryHeading& h = b.database().entry(i).heading;
    if (i < 5) {
      EXPECT_TRUE(h.unknown()) << i;
    } else {
      EXPECT_EQ(h.x, kfs[i].heading.x) << i;
      EXPECT_EQ(h.y, kfs[i].heading.y) << i;
      EXPECT_EQ(h.z, 0.f) << i;
    }
  }
  // Version 9: no headings.
  writeBytes(path, asVersion(bytes, testing::headingBytes(50), 9));
  LoopDetector c(voc, o);
  c.load(path);
  for (const DatabaseEntry& e : c.database().entries()) EXPECT_TRUE(e.heading.unknown());
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

}  // namespace
}  // namespace bowg
