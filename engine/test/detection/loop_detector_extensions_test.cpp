// LoopDetector::process with this implementation's extensions (geometric
// re-ranking, the odometry gates, windows in metres, linked places, the place
// index) on synthetic corridors (synthetic_corridor.h). The scores against
// the equations are in loop_detector_scores_test.cpp.
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
#include <utility>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/detection/place_links.h"
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

// Options of the look-alike scenarios below: word scores alone (no groups,
// no temporal score), no temporal check, every entry its own island, every
// candidate above the threshold, the 5 newest keyframes excluded.
LoopDetectorOptions lookAlikeOptions() {
  LoopDetectorOptions o = defaultOptions();
  o.word_groups.enabled = false;
  o.temporal_score.enabled = false;
  o.temporal_verification.k = 0;
  o.islands.max_intra_island_gap = 0;
  o.islands.recent_exclusion = 5;
  o.islands.min_score = 0.0;
  return o;
}

// Feeds keyframes to a detector as a robot driving along x would: each
// with the odometer and the odometry position of where it was taken.
class DrivenRun {
 public:
  explicit DrivenRun(LoopDetector* det) : det_(det) {}
  LoopResult take(KeyframeInput kf, double x) {
    driven_ += std::fabs(x - at_);
    at_ = x;
    kf.odometer = driven_;
    kf.position.x = x;
    kf.position.y = kf.position.z = 0.0;
    return det_->process(kf);
  }
  double at() const { return at_; }

 private:
  LoopDetector* det_;
  double driven_ = 0.0, at_ = 0.0;
};

// A look-alike: the query's own descriptors at shuffled positions, so its
// word score beats the true place while no epipolar geometry explains it.
// Only the best-scored island verified (the paper), the query yields no loop;
// with geometric re-ranking the true place wins.
// With `odometry_gate`, every keyframe carries the odometer and position of
// where it was taken (the look-alike after keyframe 39, at x = 40) and the
// gate is on.
LoopResult queryBehindALookAlike(int candidates, int min_inliers = 40, int rerank_ransacs = 100,
                                 bool odometry_gate = false) {
  const testing::Corridor c = testing::makeCorridor(70, 50, 5);
  std::mt19937_64 rng(11);
  LoopDetectorOptions o = lookAlikeOptions();
  o.geometric.candidates = candidates;
  o.geometric.rerank_ransacs = rerank_ransacs;
  if (odometry_gate) o.islands.odometry_gate_m = 1.0;  // drift 0.1 per metre
  // ~400 random correspondences give RANSAC ~15 chance inliers (one line
  // constraint per point); the true place gives hundreds.
  o.geometric.min_inliers = min_inliers;
  LoopDetector det(vocabulary(), o);
  DrivenRun run(&det);
  double stamp = 1.0;
  // Drives to x and takes keyframe `kf` there.
  const auto take = [&](KeyframeInput kf, double x) {
    return odometry_gate ? run.take(kf, x) : det.process(kf);
  };
  for (int i = 0; i < 40; ++i) take(testing::observeCorridor(c, i, stamp++, rng, 2, 0.5), i);
  KeyframeInput query = testing::observeCorridor(c, 10.2, 0.0, rng, 0, 0.5);
  KeyframeInput look_alike = query;  // entry 40
  // A random permutation: no homography (a reflection would be one, and
  // points related by a homography fit many fundamental matrices).
  std::shuffle(look_alike.features.keypoints.begin(), look_alike.features.keypoints.end(), rng);
  look_alike.stamp = stamp++;
  take(look_alike, 40.0);
  // Far away (entries 41..45, excluded as recent), then back near x = 10 so
  // that the query's previous keyframe is a healthy normaliser.
  for (int i = 0; i < 5; ++i)
    take(testing::observeCorridor(c, 50 + i, stamp++, rng, 2, 0.5), 50 + i);
  take(testing::observeCorridor(c, 8.2, stamp++, rng, 2, 0.5), 8.2);
  take(testing::observeCorridor(c, 9.2, stamp++, rng, 2, 0.5), 9.2);
  query.stamp = stamp++;
  const LoopResult r = take(query, 10.2);
  // The look-alike is the best-scored candidate in both cases.
  const auto& all = det.lastCandidates();
  const auto best = std::max_element(
      all.begin(), all.end(),
      [](const CandidateScores& a, const CandidateScores& b) { return a.eta < b.eta; });
  EXPECT_EQ(best->entry, 40u);
  return r;
}

TEST(LoopDetector, WithoutReRankingALookAlikeHidesTheTruePlace) {
  const LoopResult r = queryBehindALookAlike(1);
  EXPECT_EQ(r.match_id, 0u);
  EXPECT_NE(r.status, LoopStatus::kLoopDetected);
  EXPECT_EQ(r.island_first, 40u);
}

// The look-alike was taken at x = 40, 29.8 m from the query, with 61.8 m
// driven between them: the gate's radius is 1 + 0.1 * 61.8 = 7.18 m, so it
// is no candidate. The true place (x = 10, 0.2 m away, 91.8 m driven: radius
// 10.18 m) is, and without re-ranking it is the loop.
TEST(LoopDetector, OdometryGateRemovesALookAlikeTheRobotCannotBeAt) {
  const LoopResult r = queryBehindALookAlike(1, 40, 100, true);
  ASSERT_EQ(r.status, LoopStatus::kLoopDetected) << toString(r.status);
  EXPECT_GE(r.match_id, 9u);
  EXPECT_LE(r.match_id, 11u);
  EXPECT_GE(r.candidates_gated, 1u);
  EXPECT_EQ(queryBehindALookAlike(1).candidates_gated, 0u);
}

// The loop-anchored gate (odometry_anchor_m). A corridor driven at x = 0..39
// (keyframe i at x = i; keyframe 12 is a look-alike of the query: its
// descriptors at shuffled positions), then, after x = 50..54, back at x =
// 8.2 and 9.2 (the loop to 9 found with geometric re-ranking: the
// look-alike outscores it too) and the query at 10.2, verified without
// re-ranking. The absolute gate, wide after ~80 m driven (1 + 0.1 * 80 m),
// admits the look-alike 1.8 m away; it is the best-scored candidate and
// without the anchor the query has no loop. The last loop (9.2 -> keyframe
// 9) anchors the query: it drove 1.0 m since, so its place is 1.0 m past
// keyframe 9; the look-alike is 3.0 m past it, 2.0 m off, beyond the
// anchored radius 0.5 + 0.1 * (1.0 + 3.0) = 0.9 m; keyframe 10 (0.0 m off,
// radius 0.6 m) passes.
LoopResult queryNextToAnchoredLookAlike(double anchor_m, std::vector<LoopResult>* warm_up) {
  const testing::Corridor c = testing::makeCorridor(70, 50, 5);
  std::mt19937_64 rng(13);
  LoopDetectorOptions o = lookAlikeOptions();
  o.geometric.candidates = 5;
  o.geometric.min_inliers = 40;
  o.islands.odometry_gate_m = 1.0;  // drift 0.1 per metre
  o.islands.odometry_anchor_m = anchor_m;
  LoopDetector det(vocabulary(), o);
  DrivenRun run(&det);
  double stamp = 1.0;
  const auto take = [&](KeyframeInput kf, double x) {
    kf.stamp = stamp++;
    return run.take(kf, x);
  };
  KeyframeInput query = testing::observeCorridor(c, 10.2, 0.0, rng, 0, 0.5);
  for (int i = 0; i < 40; ++i) {
    if (i == 12) {
      KeyframeInput look_alike = query;
      std::shuffle(look_alike.features.keypoints.begin(), look_alike.features.keypoints.end(), rng);
      take(look_alike, 12.0);
    } else {
      take(testing::observeCorridor(c, i, 0.0, rng, 2, 0.5), i);
    }
  }
  for (int i = 0; i < 5; ++i) take(testing::observeCorridor(c, 50 + i, 0.0, rng, 2, 0.5), 50 + i);
  warm_up->push_back(take(testing::observeCorridor(c, 8.2, 0.0, rng, 2, 0.5), 8.2));
  warm_up->push_back(take(testing::observeCorridor(c, 9.2, 0.0, rng, 2, 0.5), 9.2));
  o.geometric.candidates = 1;
  det.setOptions(o);
  const LoopResult r = take(query, 10.2);
  const auto& all = det.lastCandidates();
  const auto best = std::max_element(
      all.begin(), all.end(),
      [](const CandidateScores& a, const CandidateScores& b) { return a.eta < b.eta; });
  EXPECT_EQ(best->entry, 12u);  // the look-alike is the best-scored, gate or not
  return r;
}

TEST(LoopDetector, LoopAnchorRemovesALookAlikeNearTheLastLoop) {
  std::vector<LoopResult> warm_up;
  const LoopResult without = queryNextToAnchoredLookAlike(0.0, &warm_up);
  ASSERT_EQ(warm_up.size(), 2u);
  // 8.2 follows x = 54: a low normaliser; 9.2 is the anchor.
  ASSERT_EQ(warm_up[1].status, LoopStatus::kLoopDetected) << toString(warm_up[1].status);
  EXPECT_EQ(warm_up[1].match_id, 9u);
  EXPECT_EQ(without.island_first, 12u);
  EXPECT_NE(without.status, LoopStatus::kLoopDetected);

  warm_up.clear();
  const LoopResult with = queryNextToAnchoredLookAlike(0.5, &warm_up);
  ASSERT_EQ(with.status, LoopStatus::kLoopDetected) << toString(with.status);
  EXPECT_EQ(with.match_id, 10u);
  // The absolute gate removes the far entries in both runs; the anchor
  // removes the look-alike and every other keyframe of the first pass but
  // x = 10 besides (each 1 m or more off).
  EXPECT_GE(with.candidates_gated, without.candidates_gated + 3);
}

// The anchored chain (temporal_verification.anchored_chain). A corridor
// driven at x = 0..39, then back at x = 5.2, 6.2, ... with the temporal
// check at k = 1 until a loop anchors the robot, then at k = 50 (no chain
// of islands can pass: as at 15 cm between keyframes, where a revisit
// rarely has k islands in a row). Returns the loops after the switch, each
// with the x its query was taken at.
std::vector<std::pair<double, LoopResult>> loopsAfterTheChainBecomesUnreachable(
    bool anchored_chain) {
  const testing::Corridor c = testing::makeCorridor(70, 50, 5);
  std::mt19937_64 rng(17);
  LoopDetectorOptions o = defaultOptions();
  o.word_groups.enabled = false;
  o.temporal_score.enabled = false;
  o.temporal_verification.k = 1;
  o.temporal_verification.anchored_chain = anchored_chain;
  o.islands.recent_exclusion = 5;
  o.geometric.candidates = 5;
  o.islands.odometry_gate_m = 1.0;  // drift 0.1 per metre
  o.islands.odometry_anchor_m = 0.5;
  LoopDetector det(vocabulary(), o);
  DrivenRun run(&det);
  double stamp = 1.0;
  const auto take = [&](double x) {
    return run.take(testing::observeCorridor(c, x, stamp++, rng, 2, 0.5), x);
  };
  for (int i = 0; i < 40; ++i) take(i);
  for (int i = 0; i < 5; ++i) take(50 + i);
  bool anchored = false;
  for (double x = 4.2; x < 9.0 && !anchored; x += 1.0) {
    anchored = take(x).status == LoopStatus::kLoopDetected;
  }
  EXPECT_TRUE(anchored) << "no loop at k = 1";
  o.temporal_verification.k = 50;
  det.setOptions(o);
  std::vector<std::pair<double, LoopResult>> loops;
  for (double x = run.at() + 1.0; x < 20.0; x += 1.0) {
    const LoopResult r = take(x);
    if (r.status == LoopStatus::kLoopDetected) loops.emplace_back(x, r);
    if (!anchored_chain) {
      EXPECT_EQ(r.status, LoopStatus::kNoTemporalConsistency) << toString(r.status) << " at " << x;
    }
  }
  return loops;
}

// A loop 1 m back and the odometry since it anchor each next query's place
// (radius 0.5 + 0.1 * 2 m = 0.7 <= 2 * 0.5): each passes without k islands
// in a row and its loop anchors the next; without the option none passes.
TEST(LoopDetector, ARecentLoopAnchorsTheNextQueriesWithoutTheirChain) {
  EXPECT_TRUE(loopsAfterTheChainBecomesUnreachable(false).empty());
  const std::vector<std::pair<double, LoopResult>> loops =
      loopsAfterTheChainBecomesUnreachable(true);
  EXPECT_GE(loops.size(), 8u);
  for (const auto& l : loops) {
    // Keyframe i of the first pass is at x = i.
    EXPECT_LE(std::fabs(static_cast<double>(l.second.match_id) - l.first), 1.0) << "x " << l.first;
  }
}

TEST(LoopDetector, GeometricReRankingFindsTheTruePlaceBehindALookAlike) {
  const LoopResult r = queryBehindALookAlike(5);
  ASSERT_EQ(r.status, LoopStatus::kLoopDetected) << toString(r.status);
  // Forward keyframe i is at x = i; the query is at x = 10.2.
  EXPECT_GE(r.match_id, 9u);
  EXPECT_LE(r.match_id, 11u);
  EXPECT_EQ(r.island_first, r.match_id);
  EXPECT_GE(r.inliers, 40);
  EXPECT_GT(r.timings.verification_ms, 0.0);
}

TEST(LoopDetector, ReRankingOnlyWeighsCandidatesThatCouldBeLoops) {
  // No candidate has 2,000 correspondences (each image has ~400 features),
  // so none could pass: RANSAC is not run on them and the query's island
  // is the best-scored one, the look-alike, as without re-ranking (with
  // min_inliers 40 the true place wins, above).
  const LoopResult r = queryBehindALookAlike(5, 2000);
  EXPECT_EQ(r.island_first, 40u);
  EXPECT_EQ(r.status, LoopStatus::kTooFewInliers) << toString(r.status);
  EXPECT_LT(r.correspondences, 2000);
}

// The look-alike shares every descriptor of the query, so it has the most
// correspondences of all candidates, but only chance inliers: ranked by
// correspondences alone (rerank_ransacs 0) or with one RANSAC (spent on the
// look-alike) the re-ranking keeps it and the query has no loop; the
// second RANSAC finds the true place.
TEST(LoopDetector, ReRankingRansacsGoToTheMostCorrespondencesFirst) {
  const LoopResult by_correspondences = queryBehindALookAlike(5, 40, 0);
  EXPECT_EQ(by_correspondences.island_first, 40u);
  // Verified once it passed the temporal check (k = 0 here): chance inliers.
  EXPECT_EQ(by_correspondences.status, LoopStatus::kTooFewInliers)
      << toString(by_correspondences.status);
  EXPECT_GT(by_correspondences.correspondences, 300);
  EXPECT_LT(by_correspondences.inliers, 40);

  const LoopResult one = queryBehindALookAlike(5, 40, 1);
  EXPECT_EQ(one.island_first, 40u);
  EXPECT_EQ(one.status, LoopStatus::kTooFewInliers) << toString(one.status);
  EXPECT_EQ(one.correspondences, by_correspondences.correspondences);

  const LoopResult two = queryBehindALookAlike(5, 40, 2);
  ASSERT_EQ(two.status, LoopStatus::kLoopDetected) << toString(two.status);
  EXPECT_GE(two.match_id, 9u);
  EXPECT_LE(two.match_id, 11u);
  EXPECT_GE(two.inliers, 40);
}

// Laps of one corridor: lap 0 always 0.45 m off the later query positions,
// laps 1, 2 and 3 each at the exact position on every third keyframe (0.45
// m off on the others), then lap 4 as the queries. The re-ranking's island
// jumps between laps 1, 2 and 3 from query to query, and two hypotheses per
// query cannot follow three laps: without links many queries of lap 4
// restart their chain; with the places joined by the earlier laps' loops
// they continue it. Returns lap 4's loops; `false_loops` counts those whose
// match is more than 1 m from the query.
int lastLapLoops(bool linked_places, int* false_loops) {
  const int n = 30;
  const testing::Corridor c = testing::makeCorridor(n + 12, 50, 21);
  std::mt19937_64 rng(22);
  LoopDetectorOptions o = defaultOptions();
  o.islands.recent_exclusion = 10;
  o.islands.min_score = 0.05;
  o.temporal_verification.k = 2;
  o.temporal_verification.hypotheses = 2;
  o.temporal_verification.linked_places = linked_places;
  o.geometric.candidates = 5;
  o.geometric.min_inliers = 40;
  LoopDetector det(vocabulary(), o);
  std::vector<double> x;  // every entry's position
  double stamp = 1.0;
  int loops = 0;
  *false_loops = 0;
  for (int lap = 0; lap < 5; ++lap) {
    for (int j = 0; j < n; ++j) {
      const bool exact = lap == 4 || (lap > 0 && j % 3 == lap - 1);
      x.push_back(j + (exact ? 0.0 : 0.45));
      const LoopResult r = det.process(testing::observeCorridor(c, x.back(), stamp++, rng, 2, 0.5));
      if (lap < 4 || r.status != LoopStatus::kLoopDetected) continue;
      ++loops;
      if (std::fabs(x[r.match_id] - x.back()) > 1.0) ++*false_loops;
    }
  }
  return loops;
}

TEST(LoopDetector, LinkedPlacesCarryTheChainAcrossLaps) {
  int false_without = 0, false_with = 0;
  const int without = lastLapLoops(false, &false_without);
  const int with = lastLapLoops(true, &false_with);
  EXPECT_EQ(false_without, 0);
  EXPECT_EQ(false_with, 0);
  // 9 of lap 4's 30 queries are loops without the links, 24 with them.
  EXPECT_GE(with, without + 10) << "without links " << without << ", with " << with;
}

// Four laps of a 30-place corridor (laps 2-4 0.2, 0.1 and 0.3 m off the
// first). With indexed_per_place n a keyframe whose loop makes its place
// (PlaceLinks: keyframes joined by loops) larger than n stays out of the
// inverse index: no later query lists it as a candidate, the last lap
// finds its places in the keyframes indexed before, and the index holds
// fewer postings to walk. What one run gives:
struct IndexedLaps {
  int last_lap_loops = 0, false_loops = 0;
  std::size_t size = 0, searchable = 0;
  bool rule_holds = true;          ///< every entry indexed as the rule says
  bool candidates_indexed = true;  ///< no candidate out of the index
};

IndexedLaps indexedLaps(int indexed_per_place) {
  const int n = 30, laps = 4;
  const double offsets[laps] = {0.0, 0.2, 0.1, 0.3};
  const testing::Corridor c = testing::makeCorridor(n + 12, 50, 31);
  std::mt19937_64 rng(32);
  LoopDetectorOptions o = defaultOptions();
  o.islands.recent_exclusion = 10;
  o.islands.indexed_per_place = indexed_per_place;
  LoopDetector det(vocabulary(), o);
  PlaceLinks places;  // the loops so far, as the detector links them
  IndexedLaps out;
  std::vector<double> x;
  double stamp = 1.0;
  for (int lap = 0; lap < laps; ++lap) {
    for (int j = 0; j < n; ++j) {
      x.push_back(j + offsets[lap]);
      const LoopResult r = det.process(testing::observeCorridor(c, x.back(), stamp++, rng, 2, 0.5));
      for (const CandidateScores& cs : det.lastCandidates()) {
        out.candidates_indexed &= det.database().entry(cs.entry).searchable;
      }
      const bool loop = r.status == LoopStatus::kLoopDetected;
      if (loop) places.link(r.query_id, r.match_id);
      const bool expected =
          indexed_per_place == 0 || !loop ||
          places.placeSize(r.query_id) <= static_cast<std::size_t>(indexed_per_place);
      out.rule_holds &= det.database().entry(r.query_id).searchable == expected;
      if (!loop) continue;
      if (std::fabs(x[r.match_id] - x.back()) > 1.0) ++out.false_loops;
      if (lap == laps - 1) ++out.last_lap_loops;
    }
  }
  out.size = det.database().size();
  out.searchable = det.database().searchableCount();
  return out;
}

TEST(LoopDetector, APlaceKeepsAtMostIndexedPerPlaceKeyframesInTheIndex) {
  const IndexedLaps all = indexedLaps(0), one = indexedLaps(1), two = indexedLaps(2);
  for (const IndexedLaps* run : {&all, &one, &two}) {
    EXPECT_TRUE(run->rule_holds);
    EXPECT_TRUE(run->candidates_indexed);
    EXPECT_EQ(run->false_loops, 0);
  }
  EXPECT_EQ(all.searchable, all.size);
  // Laps 2-4 closed loops, so fewer entries are indexed, the fewer the
  // smaller the limit ...
  EXPECT_LT(two.searchable + 20, all.size) << two.searchable << " of " << two.size;
  EXPECT_LT(one.searchable + 20, two.searchable) << one.searchable << " and " << two.searchable;
  // ... and the last lap still closes its loops.
  EXPECT_GE(one.last_lap_loops, 20) << "with every keyframe indexed: " << all.last_lap_loops;
  EXPECT_GE(two.last_lap_loops, 20) << "with every keyframe indexed: " << all.last_lap_loops;
}

}  // namespace
}  // namespace bowg
