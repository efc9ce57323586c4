// LoopDetector::process with this implementation's extensions (geometric
// re-ranking, windows in metres, the normaliser floor, temporal hypotheses,
// linked places)
// and its scores against eqs. 2, 4, 6-7 computed independently, on
// synthetic corridors (synthetic_corridor.h).
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

// Keyframes every 0.5 m forward (x = 0.5 i), then back over the same wall:
// keyframe ids and metres differ by a factor of 2.
std::vector<KeyframeInput> halfMetreRun(bool with_odometer) {
  const testing::Corridor c = testing::makeCorridor(45, 50, 9);
  std::mt19937_64 rng(21);
  std::vector<KeyframeInput> out;
  double driven = 0.0, x = 0.0;
  for (int i = 0; i < 120; ++i) {
    const double next = i < 70 ? 0.5 * i : 34.75 - 0.5 * (i - 70);
    if (i > 0) driven += std::fabs(next - x);
    x = next;
    out.push_back(testing::observeCorridor(c, x, 1.0 + i, rng, 2, 0.5));
    if (with_odometer) out.back().odometer = driven;
  }
  return out;
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

TEST(LoopDetector, RecentExclusionInMetresFollowsTheOdometer) {
  LoopDetectorOptions o = defaultOptions();
  o.islands.recent_exclusion = 100000;  // in keyframes: nothing is ever a candidate
  o.islands.recent_exclusion_m = 5.0;
  LoopDetector with(vocabulary(), o);
  const auto kfs = halfMetreRun(true);
  int loops = 0;
  for (std::size_t t = 0; t < kfs.size(); ++t) {
    const LoopResult r = with.process(kfs[t]);
    // Entries driven less than 5 m before the query (10 keyframes at
    // 0.5 m) are never candidates: the first 10 queries have none at all.
    if (t < 10) {
      EXPECT_EQ(r.status, LoopStatus::kDatabaseTooSmall) << t;
    }
    for (const CandidateScores& c : with.lastCandidates()) {
      EXPECT_GE(kfs[t].odometer - kfs[c.entry].odometer, 5.0)
          << "query " << t << " entry " << c.entry;
    }
    if (r.status == LoopStatus::kLoopDetected) ++loops;
  }
  EXPECT_GT(loops, 10) << "the return pass revisits 35 m of wall";
  // Without odometers the window is in keyframes again: no candidate ever.
  LoopDetector without(vocabulary(), o);
  for (const KeyframeInput& kf : halfMetreRun(false)) {
    EXPECT_EQ(without.process(kf).status, LoopStatus::kDatabaseTooSmall);
  }
}

TEST(LoopDetector, BadOdometersAreRefused) {
  LoopDetector det(vocabulary(), defaultOptions());
  auto kfs = halfMetreRun(true);
  det.process(kfs[0]);
  det.process(kfs[1]);
  KeyframeInput back = kfs[2];
  back.odometer = 0.1;  // below the last 0.5
  EXPECT_THROW(det.process(back), std::invalid_argument);
  back.odometer = -1.0;
  EXPECT_THROW(det.process(back), std::invalid_argument);
  back.odometer = std::numeric_limits<double>::infinity();
  EXPECT_THROW(det.process(back), std::invalid_argument);
  // A position is known or unknown as a whole.
  back.odometer = 1.0;
  back.position.x = 2.0;  // y and z still NaN
  EXPECT_THROW(det.process(back), std::invalid_argument);
  back.position.y = back.position.z = 0.0;
  back.position.x = std::numeric_limits<double>::infinity();
  EXPECT_THROW(det.process(back), std::invalid_argument);
  back.position = OdometryPosition();
  EXPECT_EQ(det.database().size(), 2u);
  back.odometer = std::numeric_limits<double>::quiet_NaN();  // unknown: fine
  EXPECT_NO_THROW(det.process(back));
  LoopDetectorOptions o = defaultOptions();
  o.islands.recent_exclusion_m = -1.0;
  EXPECT_THROW(LoopDetector(vocabulary(), o), InvalidParameter);
}

TEST(LoopDetector, WithoutGeometricVerificationTheIslandIsTheLoop) {
  LoopDetectorOptions o = defaultOptions();
  o.geometric.enabled = false;
  const auto s = returnStatuses(o);
  EXPECT_TRUE(contains(s, LoopStatus::kLoopDetected));
}

// eq. 2/4: eta = s(I_t, I_tj) / s(I_t, I_t-1), recomputed here from the
// stored vectors with scoreBowVectors() and the group table; eqs. 6-7 with
// the previous query's etas taken from lastCandidates().
TEST(LoopDetector, ScoresFollowTheNormaliserAndTemporalEquations) {
  LoopDetectorOptions o = defaultOptions();
  o.distribution.enabled = true;
  o.similarity.lambda_1 = 0.4;
  o.similarity.lambda_2 = 0.4;
  LoopDetector det(vocabulary(), o);
  const testing::Corridor c = testing::makeCorridor(70, 50, 3);
  std::mt19937_64 rng(9);
  std::vector<CandidateScores> previous;
  int checked = 0;
  for (int t = 0; t < 50; ++t) {
    const double x = t < 30 ? t : 59.5 - t;  // back over the first keyframes
    const KeyframeInput kf = testing::observeCorridor(c, x, 1.0 + t, rng, 2, 0.5);
    // The query's vectors as the database sees them after process().
    const LoopResult r = det.process(kf);
    const Database& db = det.database();
    const DatabaseEntry& q = db.entry(r.query_id);
    if (!det.lastCandidates().empty()) {
      ASSERT_GT(r.word_normaliser, 0.0);
      const DatabaseEntry& prev = db.entry(r.query_id - 1);
      EXPECT_NEAR(r.word_normaliser,
                  scoreBowVectors(o.scoring, det.database().bow(q.id), det.database().bow(prev.id)),
                  1e-12);
      for (const CandidateScores& cs : det.lastCandidates()) {
        const DatabaseEntry& e = db.entry(cs.entry);
        EXPECT_LT(cs.entry, r.query_id - o.islands.recent_exclusion + 1);
        // Candidates are scored through the inverse index, whose BoW
        // weights are floats (24 bits): ~1e-8 of the score.
        const double s_w =
            scoreBowVectors(o.scoring, det.database().bow(q.id), det.database().bow(e.id));
        EXPECT_NEAR(cs.eta_w * r.word_normaliser, s_w, 1e-6 * s_w);
        EXPECT_NEAR(cs.eta_d * r.distribution_normaliser,
                    distributionScore(db.distribution(r.query_id), db.distribution(cs.entry)),
                    1e-12);
        EXPECT_NEAR(cs.eta_sim, 0.4 * cs.eta_w + 0.4 * cs.eta_g + 0.2 * cs.eta_d, 1e-12);  // eq. 9
        double eta_prev = 0.0;
        for (const CandidateScores& p : previous) {
          if (p.entry + 1 == cs.entry) eta_prev = p.eta;
        }
        EXPECT_NEAR(cs.eta, temporalScore(cs.eta_sim, eta_prev, o.temporal_score), 1e-12);
        ++checked;
      }
    }
    previous = det.lastCandidates();
  }
  EXPECT_GT(checked, 20);
}

// Median of the last `window` values, computed independently of the engine.
double lastMedian(std::vector<double> v, std::size_t window) {
  if (v.size() > window) v.erase(v.begin(), v.end() - static_cast<std::ptrdiff_t>(window));
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// Normaliser floor: the scores are divided by max(s(I_t, I_t-1), floor x the
// median of the previous `window` normalisers), recomputed here from the
// normalisers the detector reported. One keyframe observed far away (a jolt)
// gives the next query an unusually small normaliser: the floor binds there.
TEST(LoopDetector, NormaliserFloorDividesByTheRecentMedianAfterAnUnusualKeyframe) {
  LoopDetectorOptions o = defaultOptions();
  o.similarity.normaliser_floor = 1.0;
  o.similarity.normaliser_window = 5;
  o.similarity.min_word_normaliser = 0.0;  // score the queries after the jolt too
  o.similarity.min_group_normaliser = 0.0;
  LoopDetector det(vocabulary(), o);
  const testing::Corridor c = testing::makeCorridor(70, 50, 3);
  std::mt19937_64 rng(9);
  std::vector<double> words, groups;  // reported s_w, s_g of keyframes 1, 2, ...
  int floored = 0, kept = 0;
  for (int t = 0; t < 50; ++t) {
    double x = t < 30 ? t : 59.5 - t;
    if (t == 40) x = 66.0;  // never seen again: shares little with its neighbours
    const LoopResult r = det.process(testing::observeCorridor(c, x, 1.0 + t, rng, 2, 0.5));
    if (!det.lastCandidates().empty()) {
      const double expected_w = std::max(r.word_normaliser, lastMedian(words, 5));
      const double expected_g = std::max(r.group_normaliser, lastMedian(groups, 5));
      EXPECT_NEAR(r.word_divisor, expected_w, 1e-12) << "query " << t;
      EXPECT_NEAR(r.group_divisor, expected_g, 1e-12) << "query " << t;
      const DatabaseEntry& q = det.database().entry(r.query_id);
      for (const CandidateScores& cs : det.lastCandidates()) {
        const DatabaseEntry& e = det.database().entry(cs.entry);
        // Float BoW weights in the inverse index: ~1e-8 of the score.
        const double s_w =
            scoreBowVectors(o.scoring, det.database().bow(q.id), det.database().bow(e.id));
        EXPECT_NEAR(cs.eta_w * r.word_divisor, s_w, 1e-6 * s_w);
      }
      (r.word_divisor > r.word_normaliser ? floored : kept) += 1;
    }
    if (t >= 1) {  // keyframe 0 has no previous keyframe, hence no normaliser
      words.push_back(r.word_normaliser);
      groups.push_back(r.group_normaliser);
    }
  }
  EXPECT_GT(floored, 0) << "the jolt should make the floor bind";
  EXPECT_GT(kept, 0) << "ordinary queries keep the paper's normaliser";
}

// With the floor, the low-normaliser test reads the floored divisor: one
// keyframe from elsewhere (a jolt) shares nothing with the next query, whose
// s(I_t, I_t-1) falls below the minimum. Without the floor the query is
// low_normaliser (the paper); with it, it is scored against the median of the
// recent normalisers.
TEST(LoopDetector, WithTheFloorADissimilarPreviousKeyframeDoesNotSilenceTheQuery) {
  for (const double floor : {0.0, 1.0}) {
    SCOPED_TRACE(floor);
    LoopDetectorOptions o = defaultOptions();
    o.islands.recent_exclusion = 0;
    o.similarity.normaliser_floor = floor;
    o.similarity.normaliser_window = 5;
    LoopDetector det(vocabulary(), o);
    const testing::Corridor a = testing::makeCorridor(20, 50, 11);
    const testing::Corridor b = testing::makeCorridor(20, 50, 12);  // other landmarks
    std::mt19937_64 rng(1);
    for (int t = 0; t < 6; ++t)
      det.process(testing::observeCorridor(a, 2.0 + 0.2 * t, 1.0 + t, rng));
    det.process(testing::observeCorridor(b, 5.0, 7.0, rng));  // the jolt
    const LoopResult r = det.process(testing::observeCorridor(a, 3.4, 8.0, rng));
    EXPECT_LT(r.word_normaliser, o.similarity.min_word_normaliser);
    if (floor == 0.0) {
      EXPECT_EQ(r.status, LoopStatus::kLowNormaliser);
      EXPECT_FALSE(r.has_candidate);
    } else {
      EXPECT_NE(r.status, LoopStatus::kLowNormaliser);
      EXPECT_GT(r.word_divisor, o.similarity.min_word_normaliser);
      EXPECT_TRUE(r.has_candidate);
    }
  }
}

// normaliser_distance_m: a robot that stops sends the same view again; the
// normaliser is then the score against the newest entry driven at least that
// far back, not against the duplicate. Keyframes 1 m apart (x = odometer =
// 0..9), then three more at x = 9 (stopped); the last one's normaliser with
// 0.5 m is s(I_t, entry 8) (odometer 8 <= 9 - 0.5), with 0 it is
// s(I_t, entry 11), the duplicate; without odometers, entry 11 too.
TEST(LoopDetector, NormaliserDistanceSkipsTheKeyframesOfAStop) {
  struct Case {
    double distance;
    bool odometry;
    EntryId expected;
  };
  for (const Case c :
       {Case{0.5, true, 8}, Case{0.0, true, 11}, Case{0.5, false, 11}, Case{2.5, true, 6}}) {
    SCOPED_TRACE(std::to_string(c.distance) + (c.odometry ? " with odometry" : " without"));
    LoopDetectorOptions o = defaultOptions();
    o.similarity.normaliser_distance_m = c.distance;
    LoopDetector det(vocabulary(), o);
    const testing::Corridor corridor = testing::makeCorridor(20, 50, 5);
    std::mt19937_64 rng(2);
    LoopResult r;
    for (int t = 0; t < 13; ++t) {
      const double x = std::min(t, 9);
      KeyframeInput kf = testing::observeCorridor(corridor, x, 1.0 + t, rng, 2, 0.5);
      if (c.odometry) kf.odometer = x;
      r = det.process(kf);
    }
    const DatabaseEntry& q = det.database().entry(r.query_id);
    const DatabaseEntry& e = det.database().entry(c.expected);
    EXPECT_NEAR(r.word_normaliser,
                scoreBowVectors(o.scoring, det.database().bow(q.id), det.database().bow(e.id)),
                1e-12);
    const DatabaseEntry& duplicate = det.database().entry(11);
    if (c.expected != 11) {
      EXPECT_LT(r.word_normaliser, scoreBowVectors(o.scoring, det.database().bow(q.id),
                                                   det.database().bow(duplicate.id)));
    }
  }
  LoopDetectorOptions bad = defaultOptions();
  bad.similarity.normaliser_distance_m = -1.0;
  EXPECT_THROW(LoopDetector(vocabulary(), bad), InvalidParameter);
}

TEST(LoopDetector, WithoutFloorTheDivisorIsTheNormaliser) {
  LoopDetector det(vocabulary(), defaultOptions());  // normaliser_floor 0
  const CorridorRun run = runCorridor(&det, true, 30);
  int checked = 0;
  for (const LoopResult& r : run.results) {
    if (r.word_divisor == 0.0) continue;  // not queried
    EXPECT_EQ(r.word_divisor, r.word_normaliser);
    EXPECT_EQ(r.group_divisor, r.group_normaliser);
    ++checked;
  }
  EXPECT_GT(checked, 5);
}

TEST(LoopDetector, OptionsChangeBetweenKeyframesRebuildsWhatDependsOnThem) {
  LoopDetectorOptions o = defaultOptions();
  o.distribution.enabled = true;
  o.distribution.fan_bins = 8;
  LoopDetector det(vocabulary(), o);
  runCorridor(&det, false, 10);
  for (EntryId id = 0; id < det.database().size(); ++id) {
    EXPECT_EQ(det.database().distribution(id).size(), 8u);
  }
  o.distribution.fan_bins = 5;
  o.geometric.direct_index_level = 2;
  o.scoring = ScoringType::kL2;
  det.setOptions(o);
  EXPECT_EQ(det.database().directLevel(), 2);
  for (const auto& e : det.database().entries()) {
    EXPECT_EQ(det.database().distribution(e.id),
              distributionVector(e.points.unpack(), e.centre_x, e.centre_y, 5));
    double n2 = 0;
    for (const auto& w : det.database().bow(e.id)) n2 += w.second * w.second;
    EXPECT_NEAR(n2, 1.0, 1e-9);  // L2-normalised now
  }
  o.similarity.lambda_1 = 2.0;
  EXPECT_THROW(det.setOptions(o), InvalidParameter);
  EXPECT_EQ(det.options().similarity.lambda_1, defaultOptions().similarity.lambda_1);
}

TEST(LoopDetector, ResetForgetsEverything) {
  LoopDetector det(vocabulary(), defaultOptions());
  runCorridor(&det, false, 5);
  det.reset();
  EXPECT_EQ(det.database().size(), 0u);
  EXPECT_EQ(det.database().groupTable().total(), 0.0);
  KeyframeInput empty;
  empty.stamp = 0.5;  // stamps may restart after a reset
  EXPECT_EQ(det.process(empty).query_id, 0u);
}

TEST(LoopDetector, StatusNamesAreDistinct) {
  std::set<std::string> names;
  for (int s = 0; s <= static_cast<int>(LoopStatus::kTooFewInliers); ++s) {
    names.insert(toString(static_cast<LoopStatus>(s)));
  }
  EXPECT_EQ(names.size(), 9u);
}

}  // namespace
}  // namespace bowg
