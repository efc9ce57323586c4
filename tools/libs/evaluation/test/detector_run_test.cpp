#include "bowg_evaluation/detector_run.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <sstream>

#include "synthetic_sequence.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace eval {
namespace {

using testing_data::syntheticSequence;

TEST(DetectorRunTest, MemoryGrowthIsPerKeyframeBetweenTheFirstAndLastSample) {
  DetectorRun run;
  EXPECT_EQ(memoryGrowth(run).keyframes, 0u);  // no samples
  run.memory = {{0, 1000.0, 100.0}, {1000, 51000.0, 40100.0}, {2500, 126000.0, 100100.0}};
  const MemoryGrowth g = memoryGrowth(run);
  EXPECT_EQ(g.keyframes, 2500u);
  EXPECT_DOUBLE_EQ(g.resident_per_keyframe, 50.0);  // (126000 - 1000) / 2500
  EXPECT_DOUBLE_EQ(g.estimate_per_keyframe, 40.0);  // (100100 - 100) / 2500
}

TEST(DetectorRunTest, OneRecordPerKeyframeAndConsistentOutputs) {
  const auto vocabulary = testing_data::syntheticSequenceVocabulary();
  const LoopDetectorOptions options = testing_data::syntheticSequenceOptions();
  const std::vector<FrameInput> frames = syntheticSequence();
  std::size_t progress_calls = 0;
  const DetectorRun run =
      runDetector(vocabulary, options, frames, "test", [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(done, ++progress_calls);
        EXPECT_EQ(total, 60u);
      });
  ASSERT_EQ(run.keyframes.size(), 60u);
  EXPECT_EQ(progress_calls, 60u);
  // Memory: before the first keyframe and after the last (60 < 1000).
  ASSERT_EQ(run.memory.size(), 2u);
  EXPECT_EQ(run.memory[0].keyframes, 0u);
  EXPECT_EQ(run.memory[1].keyframes, 60u);
  EXPECT_GT(run.memory[1].estimate_bytes, run.memory[0].estimate_bytes);
  EXPECT_GT(run.memory[0].resident_bytes, 0.0);  // Linux
  const MemoryGrowth growth = memoryGrowth(run);
  EXPECT_EQ(growth.keyframes, 60u);
  EXPECT_DOUBLE_EQ(growth.estimate_per_keyframe,
                   (run.memory[1].estimate_bytes - run.memory[0].estimate_bytes) / 60);
  std::size_t loops = 0;
  for (const KeyframeRecord& k : run.keyframes) {
    EXPECT_EQ(k.database_size, static_cast<std::size_t>(k.frame));
    if (k.has_candidate) EXPECT_LT(k.candidate, k.frame);
    if (k.status == LoopStatus::kLoopDetected) {
      ++loops;
      EXPECT_EQ(k.match, k.candidate);
    } else {
      EXPECT_EQ(k.match, -1);
    }
  }
  const std::vector<Detection> detections = detectionsOf(run);
  EXPECT_EQ(detections.size(), loops);

  GroundTruth gt;
  for (int i = 0; i < 10; ++i) gt.loops[40 + i] = {10 + i};
  const std::string csv = keyframesCsv(run, &gt);
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.substr(line.size() - 8), ",correct");
  int lines = 0, correct_flags = 0;
  while (std::getline(in, line)) {
    ++lines;
    const char last = line.back();
    if (last == '1') ++correct_flags;
    if (line.back() != ',') EXPECT_TRUE(last == '0' || last == '1');
  }
  EXPECT_EQ(lines, 60);
  // The CSV's correct flags are the true positives (one loop per query).
  EXPECT_EQ(correct_flags, evaluateAt(detections, gt, -1.0).true_positives);
  // The operating point counts every loop of the run, at the run's min_score.
  const PrPoint at = operatingPoint(run, gt);
  EXPECT_EQ(at.threshold, options.islands.min_score);
  EXPECT_EQ(at.true_positives, correct_flags);
  EXPECT_EQ(at.true_positives + at.false_positives, static_cast<int>(detections.size()));

  // Timing: feature_ms = 1..60 -> mean 30.5, max 60; keyframe total adds the
  // detector's time; the CPU time, 2..120 -> mean 61, median 61, max 120.
  const auto stats = stageTimingStats(run);
  ASSERT_EQ(stats.size(), 9u);
  EXPECT_EQ(stats[0].first, "features");
  EXPECT_DOUBLE_EQ(stats[0].second.mean, 30.5);
  EXPECT_DOUBLE_EQ(stats[0].second.max, 60);
  EXPECT_EQ(stats[7].first, "keyframe_total");
  EXPECT_GE(stats[7].second.mean, stats[0].second.mean);
  EXPECT_EQ(stats[8].first, "features_cpu");
  EXPECT_DOUBLE_EQ(stats[8].second.mean, 61);
  EXPECT_DOUBLE_EQ(stats[8].second.median, 61);
  EXPECT_DOUBLE_EQ(stats[8].second.max, 120);
  const std::vector<TimeVsSize> bins = timeVersusDatabaseSize(run, 4);
  ASSERT_EQ(bins.size(), 4u);
  EXPECT_EQ(bins.front().first, 0u);
  EXPECT_EQ(bins.back().last, 59u);
  EXPECT_EQ(bins[1].first, 15u);
}

// The threshold a run reports is the one its keyframes applied: images-only
// keyframes raise min_score by the margin (islandOptionsFor).
TEST(AppliedThreshold, FollowsTheOdometryMostKeyframesCameWith) {
  DetectorRun run;
  run.options.islands.min_score = 1.0;
  run.options.islands.images_only_score_margin = 0.1;
  EXPECT_DOUBLE_EQ(appliedThreshold(run), 1.0);  // no keyframe
  const auto add = [&run](OdometryInput input, int n) {
    for (int i = 0; i < n; ++i) {
      KeyframeRecord k;
      k.odometry_input = input;
      run.keyframes.push_back(k);
    }
  };
  add(OdometryInput::kNone, 3);
  add(OdometryInput::kOdometer, 1);
  EXPECT_DOUBLE_EQ(appliedThreshold(run), 1.1);
  add(OdometryInput::kPositions, 4);
  EXPECT_DOUBLE_EQ(appliedThreshold(run), 1.0);
  GroundTruth gt;
  EXPECT_DOUBLE_EQ(operatingPoint(run, gt).threshold, 1.0);
}

}  // namespace
}  // namespace eval
}  // namespace bowg
