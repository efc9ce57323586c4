// Missions in the loop detector and its file: which mission a keyframe and
// its loop belong to, how a robot names and continues a mission, and the
// missions section of the detector file (version 9).
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
using testing::keyframes;
using testing::options;
using testing::outPath;
using testing::putLe;
using testing::readBytes;
using testing::writeBytes;

// Mission "A" (id 1) drives the corridor forward (40 keyframes), mission "B"
// (id 2) drives back over it (25 keyframes): B's loops are into A.
void runTwoMissions(LoopDetector* d, int* loops_into_a) {
  const auto kfs = keyframes();
  d->startMission("A", 1);
  for (int i = 0; i < 40; ++i) EXPECT_EQ(d->process(kfs[i]).mission, 1u);
  d->startMission("B", 2);
  *loops_into_a = 0;
  for (std::size_t i = 40; i < kfs.size(); ++i) {
    const LoopResult r = d->process(kfs[i]);
    EXPECT_EQ(r.mission, 2u);
    if (r.status != LoopStatus::kLoopDetected) continue;
    EXPECT_EQ(r.match_mission, r.match_id < 40 ? 1u : 2u) << "match " << r.match_id;
    if (r.match_id < 40) ++*loops_into_a;
  }
}

TEST(Missions, KeyframesAndLoopsSayTheirMission) {
  LoopDetector d(testing::vocabulary(), options());
  int loops_into_a = 0;
  runTwoMissions(&d, &loops_into_a);
  EXPECT_GT(loops_into_a, 0) << "mission B revisits mission A's places";
  const MissionTable& t = d.database().missions();
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.find(1)->name, "A");
  EXPECT_EQ(t.find(1)->entries, 40u);
  EXPECT_EQ(t.find(2)->entries, 25u);
  // Each mission's positions are in a frame of its own: another run.
  EXPECT_NE(d.database().entry(39).odometry_run, d.database().entry(40).odometry_run);
  EXPECT_EQ(d.database().entry(0).mission, 1u);
  EXPECT_EQ(d.database().entry(64).mission, 2u);
}

// Mission A at corridor x = i, position (i, 0, 0); mission B drives back
// (x = 39.5 - j) with positions in a frame of its own, turned and moved:
// (5, 3 + j, 0), plus `jump` metres in y from its keyframe 10 on (an
// odometry that suddenly says the robot is elsewhere). The cross-run
// anchors compare how far each side moved from the last loop into A.
struct CrossRunOutcome {
  int loops_into_a = 0, loops_after_jump = 0, wrong_loops = 0;
  std::size_t gated_after_jump = 0;
  LoopResult last;
};
CrossRunOutcome runAcrossFrames(double jump) {
  LoopDetectorOptions o = options();
  o.islands.odometry_anchor_m = 0.3;
  o.islands.odometry_gate_drift = 0.05;
  LoopDetector d(testing::vocabulary(), o);
  std::vector<KeyframeInput> kfs = keyframes();
  for (int i = 0; i < 40; ++i) {
    kfs[i].position = OdometryPosition{double(i), 0.0, 0.0};
    kfs[i].odometer = i;
  }
  for (int j = 0; j < 25; ++j) {
    kfs[40 + j].position = OdometryPosition{5.0, 3.0 + j + (j >= 10 ? jump : 0.0), 0.0};
    kfs[40 + j].odometer = 100.0 + j;
  }
  CrossRunOutcome out;
  d.startMission("A", 1);
  for (int i = 0; i < 40; ++i) d.process(kfs[i]);
  d.startMission("B", 2);
  for (int j = 0; j < 25; ++j) {
    out.last = d.process(kfs[40 + j]);
    const bool into_a = out.last.status == LoopStatus::kLoopDetected && out.last.match_id < 40;
    out.loops_into_a += into_a ? 1 : 0;
    // B's keyframe j sees x = 39.5 - j: A's keyframes 39 - j and 40 - j.
    if (into_a && std::abs(static_cast<double>(out.last.match_id) - (39.5 - j)) > 2) {
      ++out.wrong_loops;
    }
    if (j >= 12) {
      out.loops_after_jump += into_a ? 1 : 0;
      out.gated_after_jump += out.last.candidates_gated_cross_run;
    }
  }
  return out;
}

TEST(Missions, LoopsIntoAnEarlierMissionAnchorTheNextOnes) {
  // Where B's odometry agrees, the anchors keep the true places (and
  // refuse the corridor's far look-alikes above min_score).
  const CrossRunOutcome agreed = runAcrossFrames(0.0);
  EXPECT_GT(agreed.loops_after_jump, 0);
  EXPECT_EQ(agreed.wrong_loops, 0);
  // B's odometry jumps 20 m: A's true places now lie ~20 m off the ring the
  // last loops draw, and are refused; the status says whose they were.
  const CrossRunOutcome jumped = runAcrossFrames(20.0);
  EXPECT_GT(jumped.loops_into_a, 0) << "the loops before the jump";
  EXPECT_EQ(jumped.loops_after_jump, 0);
  EXPECT_GT(jumped.gated_after_jump, agreed.gated_after_jump);
  EXPECT_EQ(jumped.wrong_loops, 0);
  ASSERT_TRUE(jumped.last.has_candidate);
  EXPECT_EQ(jumped.last.best_mission, 1u);
  EXPECT_EQ(jumped.last.best_mission_name, "A");
  EXPECT_EQ(jumped.last.mission, 2u);
  EXPECT_NE(jumped.last.status, LoopStatus::kLoopDetected);
}

TEST(Missions, ANameFindsItsMissionAgainAndAnIdOrNameIsNeverShared) {
  LoopDetector d(testing::vocabulary(), options());
  EXPECT_EQ(d.mission().id, 0u);
  EXPECT_EQ(d.mission().name, "");
  d.startMission("2025");  // no keyframe yet: the run's mission is named
  EXPECT_EQ(d.mission().id, 0u);
  EXPECT_EQ(d.database().missions().size(), 1u);
  const auto kfs = keyframes();
  d.process(kfs[0]);
  EXPECT_EQ(d.startMission("2026").id, 1u);  // the next free id
  d.process(kfs[1]);
  EXPECT_EQ(d.startMission("2025").id, 0u);  // continued
  EXPECT_EQ(d.process(kfs[2]).mission, 0u);
  EXPECT_THROW(d.startMission("2026", 7), std::invalid_argument);  // "2026" is mission 1
  EXPECT_THROW(d.startMission("2027", 1), std::invalid_argument);  // 1 is "2026"
  EXPECT_THROW(d.startMission("two\nlines"), std::invalid_argument);
  EXPECT_THROW(d.startMission("x", -2), std::invalid_argument);
  EXPECT_THROW(d.startMission("x", std::int64_t{1} << 32), std::invalid_argument);
  EXPECT_EQ(d.mission().id, 0u);
  EXPECT_EQ(d.startMission("2027", 40).id, 40u);
  EXPECT_EQ(d.database().missions().nextId(), 41u);
}

TEST(Missions, ResetKeepsTheMissionsIdAndName) {
  LoopDetector d(testing::vocabulary(), options());
  d.startMission("2026-12-05", 12);
  const auto kfs = keyframes();
  for (int i = 0; i < 5; ++i) d.process(kfs[i]);
  d.reset();
  EXPECT_TRUE(d.database().empty());
  EXPECT_EQ(d.mission().id, 12u);
  EXPECT_EQ(d.mission().name, "2026-12-05");
  EXPECT_EQ(d.database().missions().size(), 1u);
  EXPECT_EQ(d.process(kfs[0]).mission, 12u);
}

TEST(Missions, MissionsRoundTripThroughTheFile) {
  LoopDetector a(testing::vocabulary(), options());
  int loops = 0;
  runTwoMissions(&a, &loops);
  const std::string path = outPath("missions.bowgdb");
  a.save(path);
  LoopDetector b(testing::vocabulary(), options());
  b.load(path);
  ASSERT_EQ(b.database().missions().size(), 2u);
  for (const Mission& m : a.database().missions().all()) {
    const Mission* n = b.database().missions().find(m.id);
    ASSERT_NE(n, nullptr);
    EXPECT_EQ(n->name, m.name);
    EXPECT_EQ(n->entries, m.entries);
  }
  for (std::size_t i = 0; i < a.database().size(); ++i) {
    EXPECT_EQ(b.database().entry(i).mission, a.database().entry(i).mission);
  }
  EXPECT_EQ(b.mission().id, 2u);  // the robot goes on with its mission
  b.startMission("A");
  EXPECT_EQ(b.mission().id, 1u);
  std::remove(path.c_str());
}

// A file of version 8 (without missions) loads as the unnamed mission 0
// holding every entry.
TEST(Missions, AFileWithoutMissionsIsTheUnnamedMissionZero) {
  LoopDetector a(testing::vocabulary(), options());
  const auto kfs = keyframes();
  for (int i = 0; i < 30; ++i) a.process(kfs[i]);
  const std::string path = outPath("missions_v8.bowgdb");
  a.save(path);
  writeBytes(path, asVersion(readBytes(path), testing::fromVersion9Bytes(30), 8));
  LoopDetector b(testing::vocabulary(), options());
  b.load(path);
  ASSERT_EQ(b.database().missions().size(), 1u);
  EXPECT_EQ(b.database().missions().all()[0].id, 0u);
  EXPECT_EQ(b.database().missions().all()[0].name, "");
  EXPECT_EQ(b.database().missions().all()[0].entries, 30u);
  EXPECT_EQ(b.process(kfs[30]).mission, 0u);
  std::remove(path.c_str());
}

// The section of a two-mission file ("A" id 1, "B" id 2, n entries) edited
// at `offset` bytes before the entry missions, resealed, and refused with
// `why` in the message.
void expectForgedRefused(const std::string& name, long offset, std::uint32_t value,
                         const std::string& why) {
  LoopDetector a(testing::vocabulary(), options());
  int loops = 0;
  runTwoMissions(&a, &loops);
  const std::string path = outPath(name);
  a.save(path);
  std::string bytes = readBytes(path);
  const std::size_t n = a.database().size();
  // The entry missions close the version-9 section; the headings follow.
  const std::size_t entry_missions = bytes.size() - 8 - testing::headingBytes(n) - 4 * n;
  putLe(&bytes, static_cast<std::size_t>(static_cast<long>(entry_missions) + offset), value, 4);
  testing::resealChecksum(&bytes);
  writeBytes(path, bytes);
  LoopDetector b(testing::vocabulary(), options());
  try {
    b.load(path);
    ADD_FAILURE() << name << " loaded";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_TRUE(b.database().empty());
  std::remove(path.c_str());
}

// Layout before the entry missions: current (u32), count (u32), then
// id 1, length 1, "A", id 2, length 1, "B", then the count of entries.
TEST(Missions, AForgedMissionsSectionIsRefused) {
  expectForgedRefused("missions_unlisted.bowgdb", 4 * 64, 9, "belongs to mission 9");
  expectForgedRefused("missions_twice.bowgdb", -13, 1, "mission id 1 twice");
  expectForgedRefused("missions_run.bowgdb", 0, 2, "spans missions");
  expectForgedRefused("missions_current.bowgdb", -4 - 26, 5, "current mission 5");
}

}  // namespace
}  // namespace bowg
