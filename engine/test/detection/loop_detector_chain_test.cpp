// LoopDetector::process with the verified chain (VerifiedChainOptions) on a
// synthetic corridor driven twice in the same direction: loops the odometry
// does not place wait for the chain, and a verified match that does not
// follow the chain (a look-alike elsewhere) is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "bowg/detection/loop_detector.h"
#include "detection/loop_detector_runs.h"
#include "synthetic_corridor.h"

namespace bowg {
namespace {

using testing::defaultOptions;
using testing::vocabulary;

// Every island verified (no re-ranking), no temporal check of islands, the
// 5 newest keyframes excluded, every candidate above the threshold, the
// normaliser floored (the revisit follows keyframes far away): what a
// query gives is decided by geometry and, when on, the chain.
LoopDetectorOptions chainOptions(int chain) {
  LoopDetectorOptions o = defaultOptions();
  o.temporal_verification.k = 0;
  o.islands.recent_exclusion = 5;
  o.islands.recent_exclusion_m = 2.0;
  o.islands.min_score = 0.0;
  o.similarity.normaliser_floor = 1.0;
  o.geometric.min_inliers = 40;
  o.chain.length = chain;
  return o;
}

// Lap 1 at x = 0..39 (entry i at x = i), 5 keyframes far away (x = 50..54),
// then the queries at `xs`. With `odometer`, every keyframe carries the
// metres driven to it (no position: an odometer alone).
std::vector<LoopResult> drive(const LoopDetectorOptions& o, const std::vector<double>& xs,
                              bool odometer) {
  const testing::Corridor c = testing::makeCorridor(70, 50, 5);
  std::mt19937_64 rng(17);
  LoopDetector det(vocabulary(), o);
  double stamp = 1.0, at = 0.0, driven = 0.0;
  std::vector<LoopResult> results;
  const auto take = [&](double x) {
    KeyframeInput kf = testing::observeCorridor(c, x, stamp++, rng, 2, 0.5);
    driven += std::fabs(x - at);
    at = x;
    if (odometer) kf.odometer = driven;
    return det.process(kf);
  };
  for (int i = 0; i < 40; ++i) take(i);
  for (int i = 0; i < 5; ++i) take(50 + i);
  for (const double x : xs) results.push_back(take(x));
  return results;
}

// The second pass over x = 8..15, 0.2 m past the first pass's keyframes.
const std::vector<double> kRevisit{8.2, 9.2, 10.2, 11.2, 12.2, 13.2, 14.2, 15.2};

TEST(LoopDetectorChain, WithoutOdometryTheFirstLoopWaitsForTheChain) {
  // Without the chain every revisit query is a loop to its place.
  const std::vector<LoopResult> plain = drive(chainOptions(0), kRevisit, false);
  for (std::size_t i = 0; i < plain.size(); ++i) {
    ASSERT_EQ(plain[i].status, LoopStatus::kLoopDetected) << i;
    EXPECT_NEAR(plain[i].match_id, kRevisit[i], 1.0) << i;
    EXPECT_EQ(plain[i].odometry_input, OdometryInput::kNone);
  }
  // With a chain of 3: the first three queries have too few verified
  // matches before them; the fourth has three, and the ones after it also
  // lead back to its published loop: the same loops.
  const std::vector<LoopResult> chained = drive(chainOptions(3), kRevisit, false);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(chained[i].status, LoopStatus::kNoVerifiedChain) << i;
    EXPECT_EQ(chained[i].match_id, 0u);
  }
  for (std::size_t i = 3; i < chained.size(); ++i) {
    ASSERT_EQ(chained[i].status, LoopStatus::kLoopDetected) << i;
    EXPECT_EQ(chained[i].match_id, plain[i].match_id) << i;
  }
}

TEST(LoopDetectorChain, AVerifiedMatchThatDoesNotFollowIsRefused) {
  // After the revisit of 8-15 the robot is suddenly at x = 30.2: its match
  // passes every check of its query, but the previous query's match was 15
  // keyframes back: no step of a moving robot.
  std::vector<double> xs = kRevisit;
  xs.push_back(30.2);
  const std::vector<LoopResult> plain = drive(chainOptions(0), xs, false);
  ASSERT_EQ(plain.back().status, LoopStatus::kLoopDetected);
  EXPECT_NEAR(plain.back().match_id, 30.2, 1.0);
  const std::vector<LoopResult> chained = drive(chainOptions(2), xs, false);
  EXPECT_EQ(chained[kRevisit.size() - 1].status, LoopStatus::kLoopDetected);
  EXPECT_EQ(chained.back().status, LoopStatus::kNoVerifiedChain);
  EXPECT_EQ(chained.back().match_id, 0u);
}

TEST(LoopDetectorChain, WithAnOdometerTheChainIsFollowedInMetres) {
  // The same revisit with an odometer and a step tolerance of 0.5 m, to
  // which each match adds half the 1 m between keyframes (the island's best
  // entry is up to a keyframe off its place): 1.5 m. Then back to 14.2:
  // 1 m driven, and the match moved about 1 m back, not the 1 m forward
  // the odometer says.
  std::vector<double> xs = kRevisit;
  xs.push_back(14.2);
  LoopDetectorOptions o = chainOptions(0);
  o.temporal_verification.max_island_distance_m = 0.5;
  const std::vector<LoopResult> plain = drive(o, xs, true);
  ASSERT_EQ(plain.back().status, LoopStatus::kLoopDetected);
  EXPECT_NEAR(plain.back().match_id, 14.2, 1.0);
  EXPECT_EQ(plain.back().odometry_input, OdometryInput::kOdometer);
  o.chain.length = 3;
  const std::vector<LoopResult> chained = drive(o, xs, true);
  EXPECT_EQ(chained[2].status, LoopStatus::kNoVerifiedChain);
  for (std::size_t i = 3; i < kRevisit.size(); ++i) {
    EXPECT_EQ(chained[i].status, LoopStatus::kLoopDetected) << i;
  }
  EXPECT_EQ(chained.back().status, LoopStatus::kNoVerifiedChain);
}

TEST(LoopDetectorChain, WithImagesOnlyTheThresholdIsRaisedByItsMargin) {
  // Every revisit query closes its loop in both modes at min_score 0. With
  // a margin above the best revisit score, images-only queries have no
  // candidate left (min_score + margin), while queries with an odometer
  // keep min_score and every loop; a margin below the lowest score changes
  // nothing.
  LoopDetectorOptions o = chainOptions(0);
  const std::vector<LoopResult> images = drive(o, kRevisit, false);
  const std::vector<LoopResult> odometer = drive(o, kRevisit, true);
  double lowest = 1e9, highest = 0.0;
  for (const LoopResult& r : images) {
    ASSERT_EQ(r.status, LoopStatus::kLoopDetected);
    lowest = std::min(lowest, r.best.eta);
    highest = std::max(highest, r.best.eta);
  }
  ASSERT_GT(lowest, 0.0);
  o.islands.images_only_score_margin = highest * 1.01;
  const std::vector<LoopResult> images_high = drive(o, kRevisit, false);
  const std::vector<LoopResult> odometer_high = drive(o, kRevisit, true);
  for (std::size_t i = 0; i < kRevisit.size(); ++i) {
    EXPECT_EQ(images_high[i].status, LoopStatus::kNoScoreAboveThreshold) << i;
    ASSERT_EQ(odometer_high[i].status, odometer[i].status) << i;
    EXPECT_EQ(odometer_high[i].match_id, odometer[i].match_id) << i;
  }
  o.islands.images_only_score_margin = lowest * 0.99;
  const std::vector<LoopResult> images_low = drive(o, kRevisit, false);
  for (std::size_t i = 0; i < kRevisit.size(); ++i) {
    ASSERT_EQ(images_low[i].status, LoopStatus::kLoopDetected) << i;
    EXPECT_EQ(images_low[i].match_id, images[i].match_id) << i;
  }
}

TEST(LoopDetectorChain, UniqueInliersAreWhatTheRecentPastDoesNotSee) {
  // A chain of 1 and 100 unique inliers. The first query (8.2) has no
  // verified match before it. The second (9.2) has one (8.2 -> 8, its
  // recent past x = 50..54 far away: every inlier unique), but its own
  // recent past holds 8.2, a metre back, which sees its landmarks: few of
  // its inliers are unique. Without the demand 9.2 is a loop.
  LoopDetectorOptions o = chainOptions(1);
  const std::vector<LoopResult> plain = drive(o, kRevisit, false);
  EXPECT_EQ(plain[1].status, LoopStatus::kLoopDetected);
  o.chain.min_unique_inliers = 100;
  const std::vector<LoopResult> unique = drive(o, kRevisit, false);
  EXPECT_EQ(unique[0].status, LoopStatus::kNoVerifiedChain);
  EXPECT_EQ(unique[1].status, LoopStatus::kNoVerifiedChain);
  // More than any match's inliers (at most 600 features): nothing passes.
  o.chain.min_unique_inliers = 5000;
  for (const LoopResult& r : drive(o, kRevisit, false)) {
    EXPECT_EQ(r.status, LoopStatus::kNoVerifiedChain);
  }
}

}  // namespace
}  // namespace bowg
