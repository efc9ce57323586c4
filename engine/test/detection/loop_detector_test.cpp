// LoopDetector::process end to end on synthetic corridors (synthetic_corridor.h):
// a revisit is found with the right ids, a sequence without revisit finds
// none, and every LoopStatus comes out of a situation built for it. The
// implementation's extensions and the score equations:
// loop_detector_extensions_test.cpp.
#include "bowg/detection/loop_detector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/scoring/distribution.h"
#include "bowg/scoring/similarity.h"
#include "bowg/vocabulary/vocabulary.h"
#include "detection/loop_detector_runs.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

using testing::contains;
using testing::CorridorRun;
using testing::defaultOptions;
using testing::returnStatuses;
using testing::runCorridor;
using testing::vocabulary;

TEST(LoopDetector, FindsTheRevisitWithTheRightIds) {
  LoopDetector det(vocabulary(), defaultOptions());
  const CorridorRun run = runCorridor(&det, true);
  int loops = 0;
  for (std::size_t t = 0; t < run.results.size(); ++t) {
    const LoopResult& r = run.results[t];
    EXPECT_EQ(r.query_id, t);
    if (r.status != LoopStatus::kLoopDetected) continue;
    ++loops;
    ASSERT_GE(t, 60u) << "loop in the forward pass";
    // Keyframe i of the forward pass is at x = i. A view covers ~8 m of wall
    // (z = 5, fx = 400, 640 px): within 3 m the two views share > 60 % of
    // their landmarks, a true revisit.
    EXPECT_LE(std::fabs(run.x[r.match_id] - run.x[t]), 3.0)
        << "query " << t << " at x=" << run.x[t] << " matched " << r.match_id;
    EXPECT_GE(r.inliers, defaultOptions().geometric.min_inliers);
    EXPECT_TRUE(r.has_relative_pose);
    // Pure translation along x: R ~ identity, t ~ +-x.
    EXPECT_NEAR(r.rotation[0] + r.rotation[4] + r.rotation[8], 3.0, 0.01);
    EXPECT_GT(std::fabs(r.translation_direction[0]), 0.9);
  }
  // Return keyframe 60 + j is at x = 59.5 - j; the forward keyframes near it
  // leave the recent-exclusion window (20) from j ~ 10 on, and the temporal
  // verification needs k = 3 more: most of the remaining ~45 must be loops.
  EXPECT_GE(loops, 30) << "too few loops found";
  std::printf("[          ] %d loops in the 60 return keyframes\n", loops);
}

// Where the keyframes of the odometry tests are along the wall: 60 of them
// 1 m apart, then back, each halfway between two of the first pass.
std::vector<double> outAndBack() {
  std::vector<double> x;
  for (int i = 0; i < 60; ++i) x.push_back(i);
  for (int i = 0; i < 60; ++i) x.push_back(59.5 - i);
  return x;
}

// The corridor revisit with odometers (metres driven): loops get their
// translation in metres, the match camera's position in the query camera
// (x_match - x_query along the wall: X_Q = X_M + (x_m - x_q, 0, 0)).
TEST(LoopDetector, WithOdometersTheLoopsTranslationIsMetric) {
  for (const bool enabled : {true, false}) {
    LoopDetectorOptions o = defaultOptions();
    o.metric.enabled = enabled;
    o.metric.max_baseline_m = 2.0;  // keyframes 1 m apart
    LoopDetector det(vocabulary(), o);
    const testing::Corridor c = testing::makeCorridor(70, 50, 3);
    std::mt19937_64 rng(103);
    const std::vector<double> x = outAndBack();
    double odometer = 0;
    int loops = 0, metric = 0;
    for (std::size_t t = 0; t < x.size(); ++t) {
      if (t > 0) odometer += std::fabs(x[t] - x[t - 1]);
      KeyframeInput in = testing::observeCorridor(c, x[t], 1.0 + t, rng, 2, 0.5);
      in.odometer = odometer;
      const LoopResult r = det.process(in);
      if (r.status != LoopStatus::kLoopDetected) continue;
      ++loops;
      if (!enabled) {
        EXPECT_EQ(r.metric_status, MetricTranslationStatus::kDisabled);
        EXPECT_FALSE(r.translation_scale_known);
        continue;
      }
      if (!r.translation_scale_known) continue;
      ++metric;
      EXPECT_EQ(r.metric_status, MetricTranslationStatus::kEstimated);
      const double dx = x[r.match_id] - x[t];
      // Within 5 cm and the odometer_sigma of 5 % of the distance.
      EXPECT_NEAR(r.translation_m[0], dx, 0.05 + 0.05 * std::fabs(dx))
          << "query " << t << " match " << r.match_id;
      EXPECT_NEAR(r.translation_m[1], 0, 0.05);
      EXPECT_NEAR(r.translation_m[2], 0, 0.05);
      // The covariance says centimetres (plus the odometer's 5 % of the
      // distance along it, both times the calibration's sqrt(scale) in
      // sigma), not metres, and is symmetric.
      const double calibration = std::sqrt(MetricTranslationOptions().covariance_scale);
      for (int i = 0; i < 3; ++i) {
        EXPECT_GT(r.translation_covariance[4 * i], 0);
        EXPECT_LT(std::sqrt(r.translation_covariance[4 * i]),
                  calibration * (0.02 + 0.06 * std::fabs(dx)));
        EXPECT_EQ(r.translation_covariance[3 * i + (i + 1) % 3],
                  r.translation_covariance[3 * ((i + 1) % 3) + i]);
      }
      // The pose's direction is the metric translation's.
      const double n = std::sqrt(r.translation_m[0] * r.translation_m[0] +
                                 r.translation_m[1] * r.translation_m[1] +
                                 r.translation_m[2] * r.translation_m[2]);
      EXPECT_NEAR(r.translation_direction[0], r.translation_m[0] / n, 1e-12);
    }
    EXPECT_GE(loops, 30);
    if (enabled) EXPECT_GE(metric, loops * 3 / 4) << metric << " of " << loops;
  }
}

// The same revisit with odometry positions. True positions and a gate of
// 3 m: every estimate is within the odometry's bound (the distance plus
// 3 m). Positions that say the robot never moved, with a gate of 1 cm and
// no drift: the odometry allows 1 cm between any two keyframes, the
// revisits are 0.5-3 m apart, so no metric translation is published
// (outside_odometry) while the loops themselves still are.
TEST(LoopDetector, AMetricTranslationTheOdometryCannotAllowIsNotPublished) {
  for (const bool moved : {true, false}) {
    LoopDetectorOptions o = defaultOptions();
    o.metric.max_baseline_m = 2.0;  // keyframes 1 m apart
    o.islands.odometry_gate_m = moved ? 3.0 : 0.01;
    o.islands.odometry_gate_drift = 0.0;
    LoopDetector det(vocabulary(), o);
    const testing::Corridor c = testing::makeCorridor(70, 50, 3);
    std::mt19937_64 rng(103);
    const std::vector<double> x = outAndBack();
    double odometer = 0;
    int loops = 0, metric = 0, outside = 0;
    for (std::size_t t = 0; t < x.size(); ++t) {
      if (t > 0) odometer += std::fabs(x[t] - x[t - 1]);
      KeyframeInput in = testing::observeCorridor(c, x[t], 1.0 + t, rng, 2, 0.5);
      in.odometer = odometer;
      in.position.x = moved ? x[t] : 0.0;
      in.position.y = 0.0;
      in.position.z = 0.0;
      const LoopResult r = det.process(in);
      if (r.status != LoopStatus::kLoopDetected) continue;
      ++loops;
      if (r.translation_scale_known) {
        ++metric;
        EXPECT_EQ(r.metric_status, MetricTranslationStatus::kEstimated);
      }
      if (r.metric_status == MetricTranslationStatus::kOutsideOdometry) {
        ++outside;
        EXPECT_FALSE(r.translation_scale_known);
        EXPECT_TRUE(r.has_relative_pose);  // the direction stays
      }
    }
    EXPECT_GE(loops, 20) << (moved ? "true" : "still") << " positions";
    if (moved) {
      EXPECT_EQ(outside, 0);
      EXPECT_GE(metric, loops * 3 / 4) << metric << " of " << loops;
    } else {
      EXPECT_EQ(metric, 0);
      EXPECT_GE(outside, loops * 3 / 4) << outside << " of " << loops;
    }
  }
}

// The heading gate on the corridor's out-and-back: with the robot facing
// the same way on both passes (backing up) the return finds its loops; with
// the return pass facing 90 degrees away (as a robot turned into a cross
// pipe) every candidate of the first pass is gated, counted as the heading
// gate's, and no loop is published. With positions that place the return
// pass 1 km away too, the position gate refuses them first: gated, but not
// by the heading.
TEST(LoopDetector, TheHeadingGateRefusesPlacesTheRobotFacedAnotherWayAt) {
  enum Return { kSameWay, kTurned, kTurnedAndFar };
  for (const Return how : {kSameWay, kTurned, kTurnedAndFar}) {
    SCOPED_TRACE(how);
    LoopDetectorOptions o = defaultOptions();
    o.islands.heading_gate_deg = 30.0;
    o.islands.heading_gate_drift_deg = 1.5;
    o.islands.odometry_gate_m = 1.0;
    LoopDetector det(vocabulary(), o);
    const testing::Corridor c = testing::makeCorridor(70, 50, 3);
    std::mt19937_64 rng(103);
    const std::vector<double> x = outAndBack();
    double odometer = 0;
    int loops = 0;
    std::size_t gated = 0, gated_heading = 0;
    for (std::size_t t = 0; t < x.size(); ++t) {
      if (t > 0) odometer += std::fabs(x[t] - x[t - 1]);
      KeyframeInput in = testing::observeCorridor(c, x[t], 1.0 + t, rng, 2, 0.5);
      in.odometer = odometer;
      const bool back = t >= 60;
      const bool turned = back && how != kSameWay;
      in.heading.x = turned ? 0.f : 1.f;
      in.heading.y = turned ? 1.f : 0.f;
      in.heading.z = 0.f;
      if (how == kTurnedAndFar) {
        in.position.x = x[t] + (back ? 1000.0 : 0.0);
        in.position.y = in.position.z = 0.0;
      }
      const LoopResult r = det.process(in);
      gated += r.candidates_gated;
      gated_heading += r.candidates_gated_heading;
      if (r.status == LoopStatus::kLoopDetected) ++loops;
    }
    if (how == kSameWay) {
      EXPECT_GE(loops, 20);
      EXPECT_EQ(gated, 0u);
      continue;
    }
    EXPECT_EQ(loops, 0);
    EXPECT_GE(gated, 30u);
    EXPECT_EQ(gated_heading, how == kTurned ? gated : 0u);
  }
}

TEST(LoopDetector, FindsNoLoopWithoutRevisit) {
  LoopDetector det(vocabulary(), defaultOptions());
  const CorridorRun run = runCorridor(&det, false, 100);
  for (const LoopResult& r : run.results) {
    EXPECT_NE(r.status, LoopStatus::kLoopDetected) << "false loop at " << r.query_id;
  }
  EXPECT_EQ(det.database().size(), 100u);
}

TEST(LoopDetector, FirstKeyframesAreDatabaseTooSmall) {
  LoopDetectorOptions o = defaultOptions();
  o.islands.recent_exclusion = 5;
  LoopDetector det(vocabulary(), o);
  const CorridorRun run = runCorridor(&det, false, 8);
  // Keyframe t sees t entries; candidates need t > recent_exclusion.
  for (int t = 0; t <= 5; ++t) {
    EXPECT_EQ(run.results[t].status, LoopStatus::kDatabaseTooSmall) << t;
  }
  EXPECT_NE(run.results[6].status, LoopStatus::kDatabaseTooSmall);
}

TEST(LoopDetector, EmptyKeyframeIsAddedAsNoFeatures) {
  LoopDetector det(vocabulary(), defaultOptions());
  KeyframeInput empty;
  empty.stamp = 1.0;
  EXPECT_EQ(det.process(empty).status, LoopStatus::kNoFeatures);
  empty.stamp = 2.0;
  const LoopResult r = det.process(empty);
  EXPECT_EQ(r.status, LoopStatus::kNoFeatures);
  EXPECT_EQ(r.query_id, 1u);
  EXPECT_EQ(det.database().size(), 2u);
}

TEST(LoopDetector, BadInputThrowsAndIsNotAdded) {
  LoopDetector det(vocabulary(), defaultOptions());
  const testing::Corridor c = testing::makeCorridor(20, 50, 5);
  std::mt19937_64 rng(1);
  det.process(testing::observeCorridor(c, 1.0, 10.0, rng));
  KeyframeInput same_stamp = testing::observeCorridor(c, 2.0, 10.0, rng);
  EXPECT_THROW(det.process(same_stamp), std::invalid_argument);
  KeyframeInput older = testing::observeCorridor(c, 2.0, 9.0, rng);
  EXPECT_THROW(det.process(older), std::invalid_argument);
  KeyframeInput mismatch = testing::observeCorridor(c, 2.0, 11.0, rng);
  mismatch.features.descriptors.pop_back();
  EXPECT_THROW(det.process(mismatch), std::invalid_argument);
  // Stamps are ROS times or n / rate: [0, 2^32) s (a database file with
  // others is refused too).
  for (const double stamp : {std::nan(""), 1e300, kStampLimit}) {
    KeyframeInput implausible = testing::observeCorridor(c, 2.0, stamp, rng);
    EXPECT_THROW(det.process(implausible), std::invalid_argument) << stamp;
  }
  // A heading must be a direction (unit length) or unknown as a whole.
  KeyframeInput long_heading = testing::observeCorridor(c, 2.0, 11.0, rng);
  long_heading.heading.x = 2.f, long_heading.heading.y = 0.f, long_heading.heading.z = 0.f;
  EXPECT_THROW(det.process(long_heading), std::invalid_argument);
  KeyframeInput partial_heading = testing::observeCorridor(c, 2.0, 11.0, rng);
  partial_heading.heading.x = 1.f;
  EXPECT_THROW(det.process(partial_heading), std::invalid_argument);
  LoopDetector fresh(vocabulary(), defaultOptions());
  EXPECT_THROW(fresh.process(testing::observeCorridor(c, 1.0, -1.0, rng)), std::invalid_argument);
  EXPECT_EQ(fresh.process(testing::observeCorridor(c, 1.0, 0.0, rng)).query_id, 0u);
  EXPECT_EQ(det.database().size(), 1u);
  // The next valid keyframe gets id 1.
  EXPECT_EQ(det.process(testing::observeCorridor(c, 2.0, 11.0, rng)).query_id, 1u);
}

TEST(LoopDetector, LowNormaliserWhenThePreviousKeyframeSharesNothing) {
  LoopDetectorOptions o = defaultOptions();
  o.islands.recent_exclusion = 0;
  LoopDetector det(vocabulary(), o);
  const testing::Corridor a = testing::makeCorridor(20, 50, 11);
  const testing::Corridor b = testing::makeCorridor(20, 50, 12);  // other landmarks
  std::mt19937_64 rng(1);
  det.process(testing::observeCorridor(a, 5.0, 1.0, rng));
  const LoopResult r = det.process(testing::observeCorridor(b, 5.0, 2.0, rng));
  EXPECT_EQ(r.status, LoopStatus::kLowNormaliser);
  EXPECT_LT(r.word_normaliser, o.similarity.min_word_normaliser);
  EXPECT_EQ(det.database().size(), 2u);  // still added
}

// Minimum normalisers of 0 are valid, but a normaliser of exactly 0 cannot
// divide eq. 4: keypoints of size 0 form no word groups, so s_g(I_t, I_t-1) = 0
// and every candidate's eta_g would be 0/0. The keyframe must be
// low_normaliser, not a combineSimilarity exception on a NaN eta_g.
TEST(LoopDetector, ZeroNormaliserIsLowEvenWithZeroMinimum) {
  LoopDetectorOptions o = defaultOptions();
  o.islands.recent_exclusion = 0;
  o.similarity.min_word_normaliser = 0.0;
  o.similarity.min_group_normaliser = 0.0;
  o.similarity.min_distribution_normaliser = 0.0;
  LoopDetector det(vocabulary(), o);
  const testing::Corridor a = testing::makeCorridor(20, 50, 11);
  std::mt19937_64 rng(1);
  det.process(testing::observeCorridor(a, 5.0, 1.0, rng, 0, 0.0, /*size_px=*/0.f));
  LoopResult r;
  ASSERT_NO_THROW(
      r = det.process(testing::observeCorridor(a, 5.2, 2.0, rng, 0, 0.0, /*size_px=*/0.f)));
  EXPECT_GT(r.word_normaliser, 0.5);  // the words alone would be fine
  EXPECT_EQ(r.group_normaliser, 0.0);
  EXPECT_EQ(r.status, LoopStatus::kLowNormaliser);
  EXPECT_FALSE(r.has_candidate);
  EXPECT_EQ(det.database().size(), 2u);
}

// The normaliser rule applies to the ENABLED components only: keypoints of
// size 0 form no word groups, so the group normaliser is 0.
TEST(LoopDetector, GroupNormaliserCountsOnlyWhenGroupsAreOn) {
  const testing::Corridor a = testing::makeCorridor(20, 50, 11);
  for (bool groups : {true, false}) {
    LoopDetectorOptions o = defaultOptions();
    o.islands.recent_exclusion = 0;
    o.word_groups.enabled = groups;
    LoopDetector det(vocabulary(), o);
    std::mt19937_64 rng(1);
    det.process(testing::observeCorridor(a, 5.0, 1.0, rng, 0, 0.0, /*size_px=*/0.f));
    const LoopResult r =
        det.process(testing::observeCorridor(a, 5.2, 2.0, rng, 0, 0.0, /*size_px=*/0.f));
    EXPECT_GT(r.word_normaliser, 0.5);
    EXPECT_EQ(r.group_normaliser, 0.0);
    if (groups) {
      EXPECT_EQ(r.status, LoopStatus::kLowNormaliser);
    } else {
      EXPECT_NE(r.status, LoopStatus::kLowNormaliser);
      EXPECT_TRUE(r.has_candidate);  // entry 0, the same place
    }
  }
}

TEST(LoopDetector, NoCandidatesWhenOnlyExcludedEntriesShareWords) {
  LoopDetectorOptions o = defaultOptions();
  o.islands.recent_exclusion = 1;
  LoopDetector det(vocabulary(), o);
  const testing::Corridor b = testing::makeCorridor(20, 50, 12);
  std::mt19937_64 rng(1);
  KeyframeInput empty;
  empty.stamp = 1.0;
  det.process(empty);
  det.process(testing::observeCorridor(b, 5.0, 2.0, rng));
  // Entry 1 (same place, excluded) is the normaliser; entry 0 has no words.
  const LoopResult r = det.process(testing::observeCorridor(b, 5.2, 3.0, rng));
  EXPECT_EQ(r.status, LoopStatus::kNoCandidates);
  EXPECT_GT(r.word_normaliser, 0.1);
  EXPECT_FALSE(r.has_candidate);
}

TEST(LoopDetector, NoScoreAboveThresholdWithAnUnreachableThreshold) {
  LoopDetectorOptions o = defaultOptions();
  o.islands.min_score = 1e6;
  const auto s = returnStatuses(o);
  EXPECT_TRUE(contains(s, LoopStatus::kNoScoreAboveThreshold));
  EXPECT_FALSE(contains(s, LoopStatus::kLoopDetected));
}

TEST(LoopDetector, TemporalVerificationRejectsTheFirstQueriesOfARevisit) {
  LoopDetectorOptions o = defaultOptions();
  o.temporal_verification.k = 3;
  LoopDetector det(vocabulary(), o);
  const CorridorRun run = runCorridor(&det, true);
  // The first return keyframe with an island cannot have 3 consistent
  // predecessors: it must be rejected by the temporal verification.
  std::size_t first = 0;
  for (std::size_t t = 60; t < run.results.size(); ++t) {
    if (run.results[t].status != LoopStatus::kNoScoreAboveThreshold &&
        run.results[t].status != LoopStatus::kNoCandidates && run.results[t].has_candidate &&
        run.results[t].island_score > 0) {
      first = t;
      break;
    }
  }
  ASSERT_GT(first, 0u);
  EXPECT_EQ(run.results[first].status, LoopStatus::kNoTemporalConsistency);
}

TEST(LoopDetector, TooFewCorrespondencesWhenNoDescriptorIsCloseEnough) {
  LoopDetectorOptions o = defaultOptions();
  o.geometric.max_hamming = 0;  // every observation has 2 flipped bits
  const auto s = returnStatuses(o);
  EXPECT_TRUE(contains(s, LoopStatus::kTooFewCorrespondences));
  EXPECT_FALSE(contains(s, LoopStatus::kLoopDetected));
}

TEST(LoopDetector, TooFewInliersWithAnUnreachableInlierCount) {
  LoopDetectorOptions o = defaultOptions();
  o.geometric.min_inliers = 100000;
  const auto s = returnStatuses(o);
  EXPECT_TRUE(contains(s, LoopStatus::kTooFewInliers));
  EXPECT_FALSE(contains(s, LoopStatus::kLoopDetected));
}

}  // namespace
}  // namespace bowg
