// Reference maps in the offline run (reference_maps.h): the ground truth
// moved onto the run's numbering and the frames left out, by hand; a
// sequence run in one go equals its first mission saved as a map and the
// second run on it; the maps' bytes read once run as the files read per run.
#include "bowg_evaluation/reference_maps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>

#include "bowg_evaluation/mission_file.h"
#include "synthetic_sequence.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace eval {
namespace {

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The maps are the skipped frames (a re-inspection folder's first mission):
// the numbering stays the input's; skipped queries are left out.
TEST(ReferenceMaps, GroundTruthOfTheSkippedFramesKeepsItsNumbers) {
  GroundTruth gt;
  gt.loops = {{2, {0}}, {5, {1, 3}}, {7, {6}}};
  const GroundTruth moved = groundTruthAfterMaps(gt, 4, 4);
  ASSERT_EQ(moved.loops.size(), 2u);
  EXPECT_EQ(moved.loops.at(5), (std::vector<int>{1, 3}));
  EXPECT_EQ(moved.loops.at(7), (std::vector<int>{6}));
}

// Maps of 10 keyframes before an input whose first 4 frames are left out:
// input frame k >= 4 is entry 10 + (k - 4) = k + 6.
TEST(ReferenceMaps, GroundTruthMovesBehindOtherMaps) {
  GroundTruth gt;
  gt.loops = {{5, {4}}, {9, {5, 7}}};
  const GroundTruth moved = groundTruthAfterMaps(gt, 4, 10);
  ASSERT_EQ(moved.loops.size(), 2u);
  EXPECT_EQ(moved.loops.at(11), (std::vector<int>{10}));
  EXPECT_EQ(moved.loops.at(15), (std::vector<int>{11, 13}));
  // No frame left out, maps of 3: everything 3 later.
  const GroundTruth after3 = groundTruthAfterMaps(gt, 0, 3);
  EXPECT_EQ(after3.loops.at(8), (std::vector<int>{7}));
  EXPECT_EQ(after3.loops.at(12), (std::vector<int>{8, 10}));
}

TEST(ReferenceMaps, AMatchAmongSkippedFramesThatAreNotTheMapsIsRefused) {
  GroundTruth gt;
  gt.loops = {{6, {1}}};
  try {
    groundTruthAfterMaps(gt, 4, 10);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("frame 6 a match at frame 1"), std::string::npos)
        << e.what();
  }
}

TEST(ReferenceMaps, SkippingKeepsTheMissionStartedAmongTheSkippedFrames) {
  std::vector<FrameInput> frames(6);
  for (int i = 0; i < 6; ++i) frames[i].stamp = i;
  frames[0].starts_mission = true;
  frames[0].mission_id = 1;
  frames[0].mission_name = "a";
  frames[2].starts_mission = true;
  frames[2].mission_id = 2;
  frames[2].mission_name = "b";
  skipFrames(3, &frames);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_DOUBLE_EQ(frames[0].stamp, 3.0);
  EXPECT_TRUE(frames[0].starts_mission);
  EXPECT_EQ(frames[0].mission_id, 2);
  EXPECT_EQ(frames[0].mission_name, "b");
  EXPECT_THROW(skipFrames(3, &frames), std::invalid_argument);  // none would be left
}

TEST(ReferenceMaps, LiveStampsMoveBehindTheMapsOnlyWhenNeeded) {
  ReferenceMapSummary maps;
  maps.entries = 5;
  maps.last_stamp = 10.0;
  std::vector<FrameInput> frames(3);
  for (int i = 0; i < 3; ++i) frames[i].stamp = 0.5 * i;
  EXPECT_DOUBLE_EQ(stampsAfterMaps(maps, 0.5, &frames), 10.5);
  EXPECT_DOUBLE_EQ(frames[0].stamp, 10.5);
  EXPECT_DOUBLE_EQ(frames[2].stamp, 11.5);
  EXPECT_DOUBLE_EQ(stampsAfterMaps(maps, 0.5, &frames), 0.0);  // already after
  EXPECT_DOUBLE_EQ(frames[0].stamp, 10.5);
}

// A new survey's odometer counts from 0 again; the maps' last keyframe
// drove 28.4 m: the live odometers continue from there (0 -> 28.4, 1.5 ->
// 29.9), a frame without one keeps none; odometers already beyond stay.
TEST(ReferenceMaps, LiveOdometersContinueTheMaps) {
  ReferenceMapSummary maps;
  maps.entries = 5;
  maps.last_odometer = 28.4;
  std::vector<FrameInput> frames(3);
  frames[0].odometer = 0.0;
  frames[2].odometer = 1.5;
  EXPECT_DOUBLE_EQ(odometersAfterMaps(maps, &frames), 28.4);
  EXPECT_DOUBLE_EQ(frames[0].odometer, 28.4);
  EXPECT_TRUE(std::isnan(frames[1].odometer));
  EXPECT_DOUBLE_EQ(frames[2].odometer, 29.9);
  EXPECT_DOUBLE_EQ(odometersAfterMaps(maps, &frames), 0.0);  // 28.4 is not above: shift 0
  frames[0].odometer = 30.0;
  EXPECT_DOUBLE_EQ(odometersAfterMaps(maps, &frames), 0.0);
  EXPECT_DOUBLE_EQ(frames[0].odometer, 30.0);
  ReferenceMapSummary without;  // maps without odometers
  EXPECT_DOUBLE_EQ(odometersAfterMaps(without, &frames), 0.0);
}

void expectSameRecord(const KeyframeRecord& a, const KeyframeRecord& b) {
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_EQ(a.status, b.status) << "frame " << a.frame;
  EXPECT_EQ(a.candidate, b.candidate) << "frame " << a.frame;
  EXPECT_DOUBLE_EQ(a.candidate_score, b.candidate_score) << "frame " << a.frame;
  EXPECT_EQ(a.match, b.match) << "frame " << a.frame;
  EXPECT_EQ(a.inliers, b.inliers) << "frame " << a.frame;
  EXPECT_EQ(a.mission, b.mission) << "frame " << a.frame;
  EXPECT_EQ(a.database_size, b.database_size) << "frame " << a.frame;
}

TEST(ReferenceMaps, FirstMissionAsAMapGivesTheSameSecondMission) {
  std::vector<FrameInput> frames = testing_data::syntheticSequence();  // 60 frames
  attachMissions(parseMissionStarts("0,3,first\n30,9,second\n", "m"), &frames);
  const auto vocabulary = testing_data::syntheticSequenceVocabulary();
  const LoopDetectorOptions options = testing_data::syntheticSequenceOptions();
  const DetectorRun whole = runDetector(vocabulary, options, frames, "whole");

  const std::string path = ::testing::TempDir() + "/reference_maps_test_first.map";
  const std::vector<FrameInput> first(frames.begin(), frames.begin() + 30);
  RunMaps save;
  save.save = path;
  runDetector(vocabulary, options, first, "first", nullptr, save);
  const ReferenceMapSummary summary = readReferenceMaps({path}, vocabulary, options);
  EXPECT_EQ(summary.entries, 30u);
  EXPECT_DOUBLE_EQ(summary.last_stamp, frames[29].stamp);
  ASSERT_EQ(summary.missions.size(), 1u);
  EXPECT_EQ(summary.missions[0].id, 3u);
  EXPECT_EQ(summary.missions[0].name, "first");

  const std::vector<FrameInput> second(frames.begin() + 30, frames.end());
  const DetectorRun on_map =
      runDetector(vocabulary, options, second, "second", nullptr, RunMaps{{path}, 30, ""});
  ASSERT_EQ(on_map.keyframes.size(), 30u);
  ASSERT_EQ(on_map.map_missions.size(), 30u);
  EXPECT_EQ(missionOfEntry(on_map, 0), 3u);
  EXPECT_EQ(missionOfEntry(on_map, 30), 9u);
  for (int i = 0; i < 30; ++i) expectSameRecord(on_map.keyframes[i], whole.keyframes[30 + i]);
  // Loops into the map were found, and score alike across missions.
  GroundTruth gt;
  for (int i = 0; i < 10; ++i) gt.loops[40 + i] = {10 + i};
  const PrPoint a = crossMissionPoint(whole, gt), b = crossMissionPoint(on_map, gt);
  EXPECT_GT(b.true_positives, 0);
  EXPECT_EQ(a.true_positives, b.true_positives);
  EXPECT_EQ(a.false_positives, b.false_positives);
  // A map that no longer holds what was counted is refused.
  EXPECT_THROW(runDetector(vocabulary, options, second, "x", nullptr, RunMaps{{path}, 29, ""}),
               std::logic_error);
  // The map's bytes, read once, serve every run: the file is not read again.
  ASSERT_TRUE(summary.bytes);
  EXPECT_EQ(*summary.bytes, fileBytes(path));
  std::remove(path.c_str());
  const DetectorRun on_bytes = runDetector(vocabulary, options, second, "second", nullptr,
                                           RunMaps{{path}, 30, "", summary.bytes});
  ASSERT_EQ(on_bytes.keyframes.size(), 30u);
  for (int i = 0; i < 30; ++i) expectSameRecord(on_bytes.keyframes[i], on_map.keyframes[i]);
}

// Two maps: their merge, read once, runs as the files merged per run do.
TEST(ReferenceMaps, TwoMapsMergedOnceRunAsTheFilesMergedPerRun) {
  std::vector<FrameInput> frames = testing_data::syntheticSequence();  // 60 frames
  attachMissions(parseMissionStarts("0,3,first\n15,4,middle\n30,9,second\n", "m"), &frames);
  const auto vocabulary = testing_data::syntheticSequenceVocabulary();
  const LoopDetectorOptions options = testing_data::syntheticSequenceOptions();
  const std::vector<std::string> paths = {::testing::TempDir() + "/reference_maps_test_a.map",
                                          ::testing::TempDir() + "/reference_maps_test_b.map"};
  for (int part = 0; part < 2; ++part) {
    RunMaps save;
    save.save = paths[part];
    runDetector(
        vocabulary, options,
        std::vector<FrameInput>(frames.begin() + 15 * part, frames.begin() + 15 * part + 15),
        "part", nullptr, save);
  }
  EXPECT_EQ(mapsSource(paths), "the merge of " + paths[0] + ", " + paths[1]);
  EXPECT_EQ(mapsSource({paths[0]}), paths[0]);
  const ReferenceMapSummary summary = readReferenceMaps(paths, vocabulary, options);
  EXPECT_EQ(summary.entries, 30u);
  ASSERT_EQ(summary.missions.size(), 2u);
  ASSERT_TRUE(summary.bytes);
  const std::vector<FrameInput> second(frames.begin() + 30, frames.end());
  const DetectorRun per_run =
      runDetector(vocabulary, options, second, "files", nullptr, RunMaps{paths, 30, ""});
  for (const std::string& path : paths) std::remove(path.c_str());
  const DetectorRun once = runDetector(vocabulary, options, second, "bytes", nullptr,
                                       RunMaps{paths, 30, "", summary.bytes});
  ASSERT_EQ(once.keyframes.size(), 30u);
  EXPECT_EQ(once.map_missions, per_run.map_missions);
  for (int i = 0; i < 30; ++i) expectSameRecord(once.keyframes[i], per_run.keyframes[i]);
}

}  // namespace
}  // namespace eval
}  // namespace bowg
