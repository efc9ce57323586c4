// Runs side by side give exactly what the same runs give one after the other;
// the first error of any run reaches the caller; the rerun PR curve has one
// point per threshold, each the evaluation of a run at that min_score.
#include "bowg_evaluation/parallel_runs.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>

#include "bowg/core/errors.h"
#include "synthetic_sequence.h"

namespace bowg {
namespace eval {
namespace {

using testing_data::syntheticSequence;
using testing_data::syntheticSequenceOptions;
using testing_data::syntheticSequenceVocabulary;

void expectSameRecords(const DetectorRun& a, const DetectorRun& b) {
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    const KeyframeRecord &x = a.keyframes[i], &y = b.keyframes[i];
    EXPECT_EQ(x.status, y.status) << a.name << " keyframe " << i;
    EXPECT_EQ(x.candidate, y.candidate);
    EXPECT_EQ(x.candidate_score, y.candidate_score);
    EXPECT_EQ(x.match, y.match);
    EXPECT_EQ(x.inliers, y.inliers);
  }
}

TEST(ParallelRuns, SideBySideEqualsOneAfterTheOther) {
  const auto voc = syntheticSequenceVocabulary();
  const std::vector<FrameInput> frames = syntheticSequence();
  std::vector<RunRequest> requests;
  for (const char* row : {"bow", "word_groups", "temporal", "distribution"}) {
    requests.push_back({row, LoopDetectorOptions::ablation(row, syntheticSequenceOptions())});
  }
  requests.push_back({"strict", syntheticSequenceOptions()});
  requests.back().options.islands.min_score = 5.0;
  std::size_t calls = 0;
  const std::vector<DetectorRun> parallel =
      runDetectorsInParallel(voc, requests, frames, 2, [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(done, ++calls);
        EXPECT_EQ(total, requests.size());
      });
  EXPECT_EQ(calls, requests.size());
  ASSERT_EQ(parallel.size(), requests.size());
  int loops = 0;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    expectSameRecords(parallel[i], runDetector(voc, requests[i].options, frames, requests[i].name));
    loops += static_cast<int>(detectionsOf(parallel[i]).size());
  }
  EXPECT_GT(loops, 0) << "the sequence's revisit should give loops";
  // jobs 0 = one per core; more jobs than runs is fine.
  expectSameRecords(runDetectorsInParallel(voc, {requests[0]}, frames, 0)[0], parallel[0]);
  expectSameRecords(runDetectorsInParallel(voc, {requests[0]}, frames, 8)[0], parallel[0]);
  EXPECT_TRUE(runDetectorsInParallel(voc, {}, frames, 2).empty());
  EXPECT_THROW(runDetectorsInParallel(voc, requests, frames, -1), std::invalid_argument);
}

TEST(ParallelRuns, TheFirstErrorReachesTheCaller) {
  std::vector<RunRequest> requests(3, RunRequest{"ok", syntheticSequenceOptions()});
  requests[1].name = "bad";
  requests[1].options.similarity.lambda_1 = 2.0;  // LoopDetector refuses it
  EXPECT_THROW(
      runDetectorsInParallel(syntheticSequenceVocabulary(), requests, syntheticSequence(), 2),
      InvalidParameter);
}

TEST(ParallelRuns, RerunCurveHasOnePointPerThreshold) {
  const auto voc = syntheticSequenceVocabulary();
  const std::vector<FrameInput> frames = syntheticSequence();
  GroundTruth gt;
  for (int i = 0; i < 10; ++i) gt.loops[40 + i] = {10 + i};
  const std::vector<double> thresholds = {50.0, 0.3, 0.05};
  const std::vector<PrPoint> curve =
      rerunPrCurve(voc, syntheticSequenceOptions(), frames, gt, thresholds, 2);
  ASSERT_EQ(curve.size(), 3u);
  for (std::size_t i = 0; i < curve.size(); ++i) {
    LoopDetectorOptions o = syntheticSequenceOptions();
    o.islands.min_score = thresholds[i];
    const PrPoint expected = evaluateAt(detectionsOf(runDetector(voc, o, frames, "x")), gt,
                                        -std::numeric_limits<double>::infinity());
    EXPECT_EQ(curve[i].threshold, thresholds[i]);
    EXPECT_EQ(curve[i].true_positives, expected.true_positives);
    EXPECT_EQ(curve[i].false_positives, expected.false_positives);
  }
  EXPECT_EQ(curve[0].true_positives + curve[0].false_positives, 0) << "nothing scores 50";
  EXPECT_GT(curve[2].true_positives, 0);
}

}  // namespace
}  // namespace eval
}  // namespace bowg
