// The missions of a sequence (mission_file.h): the file's rules, the frames
// that start a mission, the detector run's missions and the loops across
// missions scored by hand.
#include "bowg_evaluation/mission_file.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "bowg/core/errors.h"
#include "synthetic_sequence.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace eval {
namespace {

TEST(MissionFile, ParsesTheGeneratorsFormat) {
  const std::vector<MissionStart> m = parseMissionStarts(
      "# first_frame,mission_id,name\n0,1,first survey\n\n120,7,2026, after the repair\r\n", "m");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].first_frame, 0);
  EXPECT_EQ(m[0].id, 1u);
  EXPECT_EQ(m[0].name, "first survey");
  EXPECT_EQ(m[1].first_frame, 120);
  EXPECT_EQ(m[1].id, 7u);
  EXPECT_EQ(m[1].name, "2026, after the repair");  // the rest of the line
}

void expectRefused(const std::string& text, const std::string& why) {
  try {
    parseMissionStarts(text, "missions.csv");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("missions.csv:"), std::string::npos) << e.what();
  }
}

TEST(MissionFile, BreakingTheRulesIsRefusedWithTheLine) {
  expectRefused("", "no mission");
  expectRefused("5,1,a\n", "starts at frame 0");
  expectRefused("0,1,a\n0,2,b\n", "the others after it");
  expectRefused("0,1,a\n10,1,b\n", "mission id twice");
  expectRefused("0,1,a\n10,2,a\n", "mission name twice");
  expectRefused("0,1\n", "expected first_frame,mission_id,name");
  expectRefused("x,1,a\n", "first_frame");
  expectRefused("0,-1,a\n", "mission_id");
  expectRefused("0,1.5,a\n", "mission_id");
  expectRefused("0,1,tab\there\n", "control character");
}

TEST(MissionFile, MissionsStartAtTheirFramesInTheDetectorRun) {
  std::vector<FrameInput> frames = testing_data::syntheticSequence();  // 60 frames
  attachMissions(parseMissionStarts("0,3,a\n30,9,b\n", "m"), &frames);
  EXPECT_TRUE(frames[0].starts_mission);
  EXPECT_TRUE(frames[30].starts_mission);
  EXPECT_EQ(frames[30].mission_name, "b");
  EXPECT_FALSE(frames[29].starts_mission);
  std::vector<FrameInput> short_run(frames.begin(), frames.begin() + 30);
  EXPECT_THROW(attachMissions(parseMissionStarts("0,3,a\n30,9,b\n", "m"), &short_run),
               std::invalid_argument);

  const auto vocabulary = testing_data::syntheticSequenceVocabulary();
  const LoopDetectorOptions options = testing_data::syntheticSequenceOptions();
  const DetectorRun run = runDetector(vocabulary, options, frames, "missions");
  EXPECT_EQ(run.keyframes[0].mission, 3u);
  EXPECT_EQ(run.keyframes[29].mission, 3u);
  EXPECT_EQ(run.keyframes[30].mission, 9u);
  EXPECT_EQ(run.keyframes[59].mission, 9u);
  // Frames 40-49 repeat 10-19 (another mission's): found across missions.
  GroundTruth gt;
  for (int i = 0; i < 10; ++i) gt.loops[40 + i] = {10 + i};
  const PrPoint p = crossMissionPoint(run, gt);
  EXPECT_EQ(p.positives, 10);
  EXPECT_EQ(p.false_positives, 0);
  EXPECT_GT(p.true_positives, 0);
}

// Frames 0-3 mission 1, 4-9 mission 2. Loops: 5 -> 1 (true, across),
// 6 -> 2 (false, across), 8 -> 4 (true, within: left out), 9 -> 0 (query 9
// has no match across: false). Ground truth: 5: {1}, 6: {3}, 7: {2, 4},
// 8: {4}. Across: positives 5, 6, 7 (7's match 2; 8's only match is within).
// TP 1 (5), FP 2 (6, 9): precision 1/3, recall 1/3.
TEST(MissionFile, LoopsAcrossMissionsAreScoredOnTheirOwn) {
  DetectorRun run;
  for (int i = 0; i < 10; ++i) {
    KeyframeRecord k;
    k.frame = i;
    k.mission = i < 4 ? 1 : 2;
    run.keyframes.push_back(k);
  }
  const int loops[4][2] = {{5, 1}, {6, 2}, {8, 4}, {9, 0}};
  for (const auto& l : loops) {
    run.keyframes[l[0]].status = LoopStatus::kLoopDetected;
    run.keyframes[l[0]].match = l[1];
    run.keyframes[l[0]].candidate_score = 1.0;
  }
  GroundTruth gt;
  gt.loops = {{5, {1}}, {6, {3}}, {7, {2, 4}}, {8, {4}}};
  const PrPoint p = crossMissionPoint(run, gt);
  EXPECT_EQ(p.positives, 3);
  EXPECT_EQ(p.true_positives, 1);
  EXPECT_EQ(p.false_positives, 2);
  EXPECT_DOUBLE_EQ(p.precision, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(p.recall, 1.0 / 3.0);
}

}  // namespace
}  // namespace eval
}  // namespace bowg
