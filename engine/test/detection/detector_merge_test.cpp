// Merging detector files (detector_merge.h): one database of several
// missions that finds the loops between them, the merge of a merge equal to
// the merge of the parts, and the files that do not go together refused.
#include "bowg/detection/detector_merge.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "bowg/core/atomic_file.h"
#include "detection/detector_file_runs.h"

namespace bowg {
namespace {

using testing::keyframes;
using testing::options;
using testing::outPath;
using testing::readBytes;
using testing::writeBytes;

// A file of one mission: keyframes [first, last) of the corridor run, with
// an odometer that starts at 0 in every mission, saved to `name`.
std::string missionFile(const std::string& name, const std::string& mission, std::int64_t id,
                        int first, int last, std::uint64_t vocabulary_seed = 7) {
  LoopDetector d(testing::vocabulary(vocabulary_seed), options());
  d.startMission(mission, id);
  const auto kfs = keyframes();
  for (int i = first; i < last; ++i) {
    KeyframeInput kf = kfs[i];
    kf.odometer = 0.5 * (i - first);
    d.process(kf);
  }
  const std::string path = outPath(name);
  d.save(path);
  return path;
}

// Reference maps loaded beside a running survey: the running detector's
// keyframes (mission "2026", keyframes 40-51 of the corridor run, driving
// back over the first survey's places) come after the map's, stay its
// current mission, and its next keyframes find loops into the map. A map
// holding the running mission's id is refused naming both.
TEST(DetectorMerge, AMapLoadedBesideARunningSurveyKeepsTheSurvey) {
  const std::string a = missionFile("running_a.bowgdb", "2025", 1, 0, 40);
  const auto vocabulary = testing::vocabulary();
  LoopDetector d(vocabulary, options());
  d.startMission("2026", 2);
  const auto kfs = keyframes();
  for (int i = 40; i < 46; ++i) d.process(kfs[i]);
  d.adopt(LoopDetector::readMergedWithRunning({a}, d.serialize(), vocabulary));
  const Database& db = d.database();
  ASSERT_EQ(db.size(), 46u);
  EXPECT_EQ(db.entry(0).mission, 1u);
  EXPECT_EQ(db.entry(40).mission, 2u);
  EXPECT_EQ(d.mission().id, 2u);
  EXPECT_EQ(d.mission().name, "2026");
  int into_map = 0;
  for (std::size_t i = 46; i < kfs.size(); ++i) {
    const LoopResult r = d.process(kfs[i]);
    EXPECT_EQ(r.mission, 2u);
    if (r.status == LoopStatus::kLoopDetected && r.match_mission == 1u) ++into_map;
  }
  EXPECT_GT(into_map, 0);

  LoopDetector same_id(vocabulary, options());
  same_id.startMission("another 2025", 1);
  same_id.process(kfs[40]);
  try {
    LoopDetector::readMergedWithRunning({a}, same_id.serialize(), vocabulary);
    ADD_FAILURE() << "a map holding the running mission's id was merged";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the running database"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(a), std::string::npos) << e.what();
  }
  EXPECT_THROW(LoopDetector::readMergedWithRunning({}, d.serialize(), vocabulary),
               std::invalid_argument);
}

TEST(DetectorMerge, TheMergedDatabaseHoldsBothMissionsAndFindsLoopsBetweenThem) {
  const std::string a = missionFile("merge_a.bowgdb", "2025", 1, 0, 40);
  const std::string b = missionFile("merge_b.bowgdb", "2026", 2, 40, 52);
  const std::string merged = outPath("merge_ab.bowgdb");
  writeFileAtomically(merged, mergeDetectorFiles({b, a}, testing::vocabulary()));
  LoopDetector d(testing::vocabulary(), options());
  d.load(merged);
  const Database& db = d.database();
  ASSERT_EQ(db.size(), 52u);
  ASSERT_EQ(db.missions().size(), 2u);
  EXPECT_EQ(db.missions().all()[0].name, "2025");  // stamp order, not argument order
  EXPECT_EQ(db.missions().find(1)->entries, 40u);
  EXPECT_EQ(db.missions().find(2)->entries, 12u);
  EXPECT_EQ(db.entry(39).mission, 1u);
  EXPECT_EQ(db.entry(40).mission, 2u);
  // Metres driven continue over the database; each mission its own run.
  EXPECT_DOUBLE_EQ(db.entry(39).odometer, 19.5);
  EXPECT_DOUBLE_EQ(db.entry(40).odometer, 19.5);
  EXPECT_DOUBLE_EQ(db.entry(51).odometer, 25.0);
  EXPECT_NE(db.entry(39).odometry_run, db.entry(40).odometry_run);
  EXPECT_EQ(d.mission().id, 2u);
  // A third mission driving back over the corridor finds both.
  d.startMission("2027", 3);
  const auto kfs = keyframes();
  int into_first = 0;
  for (std::size_t i = 52; i < kfs.size(); ++i) {
    const LoopResult r = d.process(kfs[i]);
    if (r.status == LoopStatus::kLoopDetected && r.match_mission == 1) ++into_first;
  }
  EXPECT_GT(into_first, 0);
  for (const std::string& p : {a, b, merged}) std::remove(p.c_str());
}

TEST(DetectorMerge, TheMergeOfAMergeIsTheMergeOfTheParts) {
  const auto voc = testing::vocabulary();
  const std::string a = missionFile("mm_a.bowgdb", "a", 1, 0, 20);
  const std::string b = missionFile("mm_b.bowgdb", "b", 2, 20, 35);
  const std::string c = missionFile("mm_c.bowgdb", "c", 3, 35, 50);
  const std::string ab = outPath("mm_ab.bowgdb");
  writeFileAtomically(ab, mergeDetectorFiles({a, b}, voc));
  const std::string all = mergeDetectorFiles({a, b, c}, voc);
  EXPECT_EQ(mergeDetectorFiles({ab, c}, voc), all);
  EXPECT_EQ(mergeDetectorFiles({c, a, b}, voc), all);
  // A merged file loads with every mission.
  const std::string abc = outPath("mm_abc.bowgdb");
  writeFileAtomically(abc, all);
  LoopDetector d(voc, options());
  d.load(abc);
  ASSERT_EQ(d.database().missions().size(), 3u);
  EXPECT_EQ(d.database().missions().find(1)->entries, 20u);
  EXPECT_EQ(d.database().missions().find(2)->entries, 15u);
  EXPECT_EQ(d.database().missions().find(3)->entries, 15u);
  for (const std::string& p : {a, b, c, ab, abc}) std::remove(p.c_str());
}

// A detector starting on two earlier missions as reference maps finds the
// places of both.
TEST(DetectorMerge, ADetectorReadsSeveralReferenceMapsAtOnce) {
  const auto voc = testing::vocabulary();
  const std::string a = missionFile("ref_a.bowgdb", "first half", 1, 0, 20);
  const std::string b = missionFile("ref_b.bowgdb", "second half", 2, 20, 40);
  LoopDetector d(voc, options());
  d.adopt(LoopDetector::readMerged({b, a}, voc, d.options()));
  EXPECT_EQ(d.database().size(), 40u);
  EXPECT_EQ(d.startMission("live", 3).id, 3u);
  const auto kfs = keyframes();
  std::set<std::uint32_t> found;
  for (std::size_t i = 40; i < kfs.size(); ++i) {
    const LoopResult r = d.process(kfs[i]);
    EXPECT_EQ(r.mission, 3u);
    if (r.status != LoopStatus::kLoopDetected) continue;
    EXPECT_EQ(r.match_mission, r.match_id < 20 ? 1u : 2u);
    EXPECT_EQ(r.match_mission_name, r.match_id < 20 ? "first half" : "second half");
    found.insert(r.match_mission);
  }
  EXPECT_EQ(found.size(), 2u) << "loops into both reference missions";
  // One file is read as it is, memory of previous queries included.
  LoopDetector one(voc, options());
  one.adopt(LoopDetector::readMerged({a}, voc, one.options()));
  EXPECT_EQ(one.database().size(), 20u);
  EXPECT_EQ(one.mission().id, 1u);
  for (const std::string& p : {a, b}) std::remove(p.c_str());
}

void expectRefused(const std::vector<std::string>& paths, const std::string& why) {
  try {
    mergeDetectorFiles(paths, testing::vocabulary());
    ADD_FAILURE() << "merged; expected: " << why;
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
  }
}

TEST(DetectorMerge, FilesThatDoNotGoTogetherAreRefused) {
  const std::string a = missionFile("bad_a.bowgdb", "2025", 1, 0, 20);
  const std::string b = missionFile("bad_b.bowgdb", "2026", 2, 20, 30);
  const std::string same_id = missionFile("bad_same_id.bowgdb", "2027", 1, 30, 40);
  const std::string same_name = missionFile("bad_same_name.bowgdb", "2025", 5, 30, 40);
  const std::string overlap = missionFile("bad_overlap.bowgdb", "2028", 6, 10, 25);
  const std::string foreign = missionFile("bad_foreign.bowgdb", "2029", 7, 30, 40, 99);
  expectRefused({a}, "two files or more");
  expectRefused({a, a}, "a file merged with itself");
  expectRefused({a, same_id}, "both hold mission 1");
  expectRefused({a, same_name}, "named '2025'");
  expectRefused({a, overlap}, "overlap in time");
  expectRefused({a, foreign}, "another vocabulary");
  expectRefused({a, foreign}, foreign);
  // Truncated: the file is named.
  const std::string truncated = outPath("bad_truncated.bowgdb");
  const std::string bytes = readBytes(b);
  writeBytes(truncated, bytes.substr(0, bytes.size() / 2));
  expectRefused({a, truncated}, truncated);
  expectRefused({a, outPath("no_such_file.bowgdb")}, "no_such_file.bowgdb");
  // Saved by detectors of different scorings.
  LoopDetectorOptions l2 = options();
  l2.scoring = ScoringType::kL2;
  LoopDetector d(testing::vocabulary(), l2);
  d.startMission("2030", 8);
  d.process(keyframes()[45]);
  const std::string other_scoring = outPath("bad_scoring.bowgdb");
  d.save(other_scoring);
  expectRefused({a, other_scoring}, "one configuration");
  for (const std::string& p :
       {a, b, same_id, same_name, overlap, foreign, truncated, other_scoring}) {
    std::remove(p.c_str());
  }
}

}  // namespace
}  // namespace bowg
