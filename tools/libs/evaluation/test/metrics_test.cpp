#include "bowg_evaluation/metrics.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "bowg/core/errors.h"

namespace bowg {
namespace eval {
namespace {

// Hand-made case. Ground truth: 10:{2,3} 11:{3,4} 12:{5} 13:{} 20:{8};
// P = 4 queries with a revisit.
GroundTruth handGroundTruth() {
  GroundTruth gt;
  gt.loops[10] = {2, 3};
  gt.loops[11] = {3, 4};
  gt.loops[12] = {5};
  gt.loops[13] = {};
  gt.loops[20] = {8};
  return gt;
}

// Detections, by score: 0.9 (10,3) TP; 0.8 (11,7) FP; 0.7 (12,5) TP;
// 0.6 (13,1) FP (13 has no revisit); 0.5 (20,8) TP; 0.4 (20,9) would be FP
// but query 20 already counts with its best detection (20,8).
std::vector<Detection> handDetections() {
  return {{10, 3, 0.9}, {11, 7, 0.8}, {12, 5, 0.7}, {13, 1, 0.6}, {20, 8, 0.5}, {20, 9, 0.4}};
}

TEST(MetricsTest, CountsAtAThreshold) {
  // tau = 0.7: accepted 0.9 TP, 0.8 FP, 0.7 TP: P = 2/3, R = 2/4,
  // F1 = 2 (2/3)(1/2) / (2/3 + 1/2) = (2/3) / (7/6) = 4/7.
  const PrPoint p = evaluateAt(handDetections(), handGroundTruth(), 0.7);
  EXPECT_EQ(p.true_positives, 2);
  EXPECT_EQ(p.false_positives, 1);
  EXPECT_EQ(p.positives, 4);
  EXPECT_DOUBLE_EQ(p.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(p.recall, 0.5);
  EXPECT_DOUBLE_EQ(p.f1, 4.0 / 7.0);
  // Nothing accepted: precision 1 by convention, recall 0, F1 0.
  const PrPoint none = evaluateAt(handDetections(), handGroundTruth(), 0.95);
  EXPECT_DOUBLE_EQ(none.precision, 1.0);
  EXPECT_DOUBLE_EQ(none.recall, 0.0);
  EXPECT_DOUBLE_EQ(none.f1, 0.0);
}

TEST(MetricsTest, EachQueryCountsOnceWithItsBestDetection) {
  // tau = 0.4 accepts (20,8,0.5) and (20,9,0.4): query 20 counts once, as
  // its best (0.5, a TP): TP = 3 (10, 12, 20), FP = 2 (11, 13).
  const PrPoint p = evaluateAt(handDetections(), handGroundTruth(), 0.4);
  EXPECT_EQ(p.true_positives, 3);
  EXPECT_EQ(p.false_positives, 2);
  EXPECT_DOUBLE_EQ(p.precision, 0.6);
  EXPECT_DOUBLE_EQ(p.recall, 0.75);
  // The same with the wrong detection scoring higher: query 20 is then a FP.
  std::vector<Detection> swapped = handDetections();
  swapped[5].score = 0.55;
  const PrPoint q = evaluateAt(swapped, handGroundTruth(), 0.4);
  EXPECT_EQ(q.true_positives, 2);
  EXPECT_EQ(q.false_positives, 3);
}

TEST(MetricsTest, CurveAndRecallAtFullPrecision) {
  const std::vector<PrPoint> curve = precisionRecallCurve(handDetections(), handGroundTruth());
  // One point per distinct score, descending:
  //  0.9: TP1 FP0 | 0.8: 1 1 | 0.7: 2 1 | 0.6: 2 2 | 0.5: 3 2 | 0.4: 3 2
  ASSERT_EQ(curve.size(), 6u);
  const int tp[] = {1, 1, 2, 2, 3, 3}, fp[] = {0, 1, 1, 2, 2, 2};
  const double thr[] = {0.9, 0.8, 0.7, 0.6, 0.5, 0.4};
  for (int i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(curve[i].threshold, thr[i]);
    EXPECT_EQ(curve[i].true_positives, tp[i]) << i;
    EXPECT_EQ(curve[i].false_positives, fp[i]) << i;
  }
  // Only tau = 0.9 has no FP: recall 1/4 at 100 % precision.
  const PrPoint best = recallAtFullPrecision(curve);
  EXPECT_DOUBLE_EQ(best.recall, 0.25);
  EXPECT_DOUBLE_EQ(best.threshold, 0.9);
  EXPECT_DOUBLE_EQ(best.precision, 1.0);
}

TEST(MetricsTest, RecallAtFullPrecisionIsZeroWhenTheTopScoreIsWrong) {
  std::vector<Detection> d = handDetections();
  d.push_back({11, 0, 0.99});  // a wrong loop above everything else
  const PrPoint best = recallAtFullPrecision(precisionRecallCurve(d, handGroundTruth()));
  EXPECT_DOUBLE_EQ(best.recall, 0.0);
  EXPECT_TRUE(std::isinf(best.threshold));
}

TEST(MetricsTest, TiedScoresAreAcceptedTogether) {
  // A TP and a FP with the same score: no threshold separates them, so the
  // TP does not count at 100 % precision.
  GroundTruth gt;
  gt.loops[10] = {1};
  gt.loops[11] = {2};
  const std::vector<Detection> d = {{10, 1, 0.9}, {11, 5, 0.5}, {10, 1, 0.5}};
  EXPECT_DOUBLE_EQ(recallAtFullPrecision(precisionRecallCurve(d, gt)).recall, 0.5);
  const std::vector<Detection> tie = {{10, 1, 0.5}, {11, 5, 0.5}};
  EXPECT_DOUBLE_EQ(recallAtFullPrecision(precisionRecallCurve(tie, gt)).recall, 0.0);
}

TEST(MetricsTest, CurveAtGivenThresholds) {
  const std::vector<PrPoint> c =
      precisionRecallCurve(handDetections(), handGroundTruth(), {1.0, 0.65, 0.0});
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].true_positives + c[0].false_positives, 0);
  EXPECT_EQ(c[1].true_positives, 2);  // 0.9, 0.7
  EXPECT_EQ(c[1].false_positives, 1);  // 0.8
  EXPECT_EQ(c[2].true_positives, 3);
  EXPECT_EQ(c[2].false_positives, 2);
}

TEST(MetricsTest, DetectionsCsvRoundTripAndErrors) {
  const std::vector<Detection> d = handDetections();
  const std::vector<Detection> back = parseDetectionsCsv(detectionsToCsv(d), "d.csv");
  ASSERT_EQ(back.size(), d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    EXPECT_EQ(back[i].query, d[i].query);
    EXPECT_EQ(back[i].match, d[i].match);
    EXPECT_DOUBLE_EQ(back[i].score, d[i].score);
  }
  EXPECT_THROW(parseDetectionsCsv("query,match,score\n1,2\n", "d.csv"), FormatError);
  EXPECT_THROW(parseDetectionsCsv("1,x,0.5\n", "d.csv"), FormatError);
  EXPECT_THROW(parseDetectionsCsv("1,2,0.5,7\n", "d.csv"), FormatError);
  try {
    parseDetectionsCsv("query,match,score\n1,2,0.5\n-1,2,0.5\n", "d.csv");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("d.csv:3:"), std::string::npos);
  }
}

}  // namespace
}  // namespace eval
}  // namespace bowg
