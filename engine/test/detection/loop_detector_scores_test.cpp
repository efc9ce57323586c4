// LoopDetector::process's scores against eqs. 2, 4, 6-7 computed
// independently, the normaliser floor and distance, the recent-exclusion
// window in metres and bad odometers, options changed between keyframes,
// reset, on synthetic corridors (synthetic_corridor.h).
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

// Runs `det` over keyframes of one corridor seen from x = xs[0], xs[1], ...
// (odometer = x when `odometry`); the last keyframe's result.
LoopResult processAt(LoopDetector* det, const std::vector<double>& xs, bool odometry) {
  const testing::Corridor corridor = testing::makeCorridor(20, 50, 5);
  std::mt19937_64 rng(2);
  LoopResult r;
  for (std::size_t t = 0; t < xs.size(); ++t) {
    KeyframeInput kf = testing::observeCorridor(corridor, xs[t], 1.0 + t, rng, 2, 0.5);
    if (odometry) kf.odometer = xs[t];
    r = det->process(kf);
  }
  return r;
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
    const LoopResult r = processAt(&det, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 9, 9}, c.odometry);
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

// normaliser_lookback: without odometry, a robot that slows down sends
// nearly the same view again; where s(I_t, I_t-1) exceeds
// normaliser_lookback_ratio times the median s(I_j, I_j-1) of the history,
// the normaliser is the score against the newest of the last `lookback`
// entries that looks no more like the query than that median. Keyframes 1 m
// apart (x = 0..9), then three 5 cm apart (9.05, 9.1, 9.15). The last query
// scores its previous keyframe (9.1) over 1.1 times the median; 9.05 and 9.0
// look more like it than the median, 8.0 less: with a lookback of 4 it is
// normalised by entry 8; with 3 (9.05 and 9.0 only), 1 or 0, with a ratio the
// previous keyframe does not reach, and with odometers
// (normaliser_distance_m 0), by entry 11.
TEST(LoopDetector, NormaliserLookbackSkipsTheKeyframesOfASlowDown) {
  struct Case {
    int lookback;
    double ratio;
    bool odometry;
    EntryId expected;
  };
  for (const Case c : {Case{4, 1.1, false, 8}, Case{3, 1.1, false, 11}, Case{0, 1.1, false, 11},
                       Case{1, 1.1, false, 11}, Case{4, 1.1, true, 11}, Case{4, 50, false, 11}}) {
    SCOPED_TRACE(std::to_string(c.lookback) + " " + std::to_string(c.ratio) +
                 (c.odometry ? " with odometry" : " without"));
    LoopDetectorOptions o = defaultOptions();
    o.similarity.normaliser_lookback = c.lookback;
    o.similarity.normaliser_lookback_ratio = c.ratio;
    LoopDetector det(vocabulary(), o);
    const LoopResult r =
        processAt(&det, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9.05, 9.1, 9.15}, c.odometry);
    const Database& db = det.database();
    const auto s_w = [&](EntryId a, EntryId b) {
      return scoreBowVectors(o.scoring, db.bow(a), db.bow(b));
    };
    // The history: s(I_j, I_j-1) of every earlier query (j = 1..11).
    std::vector<double> adjacent;
    for (EntryId j = 1; j <= 11; ++j) adjacent.push_back(s_w(j, j - 1));
    std::nth_element(adjacent.begin(), adjacent.begin() + 5, adjacent.end());
    const double median = adjacent[5];
    ASSERT_GT(s_w(r.query_id, 11), 1.1 * median);
    ASSERT_LT(s_w(r.query_id, 11), 50 * median);
    ASSERT_GT(s_w(r.query_id, 10), median);
    ASSERT_GT(s_w(r.query_id, 9), median);
    ASSERT_LE(s_w(r.query_id, 8), median);
    EXPECT_NEAR(r.word_normaliser, s_w(r.query_id, c.expected), 1e-12);
  }
  LoopDetectorOptions bad = defaultOptions();
  bad.similarity.normaliser_lookback = -1;
  EXPECT_THROW(LoopDetector(vocabulary(), bad), InvalidParameter);
  bad = defaultOptions();
  bad.similarity.normaliser_lookback_ratio = 0.9;
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
