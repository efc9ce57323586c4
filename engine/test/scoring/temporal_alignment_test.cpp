// The aligned previous score of the temporal score (temporal_alignment.h),
// with values worked out by hand.
#include "bowg/scoring/temporal_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "bowg/scoring/similarity.h"

namespace bowg {
namespace {

using Scores = std::vector<std::pair<EntryId, double>>;

TemporalScoreOptions window(int r) {
  TemporalScoreOptions o;
  o.alignment_window = r;
  return o;
}

TEST(AlignedPreviousScore, WindowZeroIsEquationSevenExactly) {
  const Scores previous{{4, 0.5}, {5, 0.9}, {6, 0.3}};
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 6, 0, window(0)), 0.9);  // eta(t-1, 5)
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 5, 0, window(0)), 0.5);  // eta(t-1, 4)
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 8, 0, window(0)), 0.0);  // 7 not scored
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 0, 0, window(0)), 0.0);  // no entry -1
  EXPECT_DOUBLE_EQ(alignedPreviousScore(Scores(), 5, 0, window(3)), 0.0);
  // Equal speeds: eq. 7 with w_max 0.6, alpha 0.2, eta 1.0, eta_prev 0.9:
  // d = 0.5, w_prev = 0.6 / 1.25 = 0.48, eta_temp = 0.48*0.9 + 0.52*1.0.
  TemporalScoreOptions o = window(0);
  o.w_max = 0.6;
  o.alpha = 0.2;
  EXPECT_NEAR(temporalScore(1.0, alignedPreviousScore(previous, 6, 0, o), o), 0.952, 1e-12);
}

TEST(AlignedPreviousScore, TwiceTheSpeedStillCarriesThePreviousScore) {
  // The revisit advances two database entries per query: the previous query
  // matched entry 10, this one matches entry 12. Eq. 7 reads entry 11, which
  // was not scored; a window of 1 finds entry 10.
  const Scores previous{{3, 0.4}, {10, 1.5}, {14, 0.2}};
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 12, 0, window(0)), 0.0);
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 12, 0, window(1)), 1.5);
  // w_max 0.9, alpha 1: d = (1.2 - 1.5) / 1 = -0.3, w_prev = 0.9 / 1.09 =
  // 0.825688..., eta_temp = 0.825688 * 1.5 + 0.174312 * 1.2 = 1.447706...
  TemporalScoreOptions o = window(1);
  o.w_max = 0.9;
  o.alpha = 1.0;
  const double eta_prev = alignedPreviousScore(previous, 12, 0, o);
  EXPECT_NEAR(temporalScore(1.2, eta_prev, o), 1.4477064220, 1e-9);
  // Without the window the score falls back to (1 - 0) weight on eta.
  EXPECT_NEAR(temporalScore(1.2, 0.0, o), 1.2 - 0.9 / (1 + 1.44) * 1.2, 1e-12);
}

TEST(AlignedPreviousScore, SlowerPassAndBackingUpFindTheSameOrNextEntry) {
  // Half the speed: the revisit stays on entry 10 for two queries. Window 1
  // around entry 9 (= 10 - 1) covers 8..10.
  const Scores previous{{10, 1.1}};
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 10, 0, window(1)), 1.1);
  // Backing up one entry (10 -> 9) is an offset of -1 from the diagonal's
  // +1: window 1 around entry 8 covers 7..9, window 2 covers 6..10.
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 9, 0, window(1)), 0.0);
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 9, 0, window(2)), 1.1);
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 8, 0, window(1)), 0.0);  // 6..8
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 12, 0, window(1)), 1.1);  // 10..12
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 13, 0, window(1)), 0.0);  // 11..13
}

TEST(AlignedPreviousScore, TheBestScoreOfTheWindowWins) {
  const Scores previous{{7, 0.3}, {8, 0.8}, {9, 0.6}, {12, 2.0}};
  // Entry 10, window 2: entries 7..11 -> 0.8 (12 is outside).
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 10, 0, window(2)), 0.8);
  // Window 3: 6..12 -> 2.0.
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 10, 0, window(3)), 2.0);
}

TEST(AlignedPreviousScore, MissedQueriesMoveAndWidenTheWindow) {
  // Two queries could not be scored since the previous scores: the place
  // moved ~3 entries on. Centre 20 - 3 = 17, half-width 1 * 3: 14..20.
  const Scores previous{{13, 5.0}, {14, 0.7}, {21, 9.0}};
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 20, 2, window(1)), 0.7);
  // Window 0 with misses: entry 20 - 3 = 17 only.
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 20, 2, window(0)), 0.0);
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 16, 2, window(0)), 5.0);  // 13
  EXPECT_THROW(alignedPreviousScore(previous, 20, -1, window(1)), std::invalid_argument);
}

TEST(AlignedPreviousScore, TheWindowIsClippedAtEntryZero) {
  const Scores previous{{0, 0.25}, {2, 0.5}};
  // Entry 1, window 2: centre 0, -2..2 clipped to 0..2.
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 1, 0, window(2)), 0.5);
  // Entry 0, window 0: centre -1, nothing.
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 0, 0, window(0)), 0.0);
  // Entry 0, window 1: -2..0 -> entry 0.
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 0, 0, window(1)), 0.25);
}

TEST(AlignedPreviousScoreInMetres, FindsThePredecessorByTheMetresDriven) {
  // Entries every 0.1 m of the first pass: odometers 0.0, 0.1, ..., 2.0.
  std::vector<double> odometers;
  for (int i = 0; i <= 20; ++i) odometers.push_back(0.1 * i);
  const Scores previous{{8, 0.4}, {10, 1.3}, {11, 0.9}, {14, 2.2}};
  // The query drove 0.3 m since the previous scored query (a pass three
  // times the first one's spacing): candidate 13 (1.3 m) had its place at
  // 1.0 m, entry 10, then. Window 0.05 m: [0.95, 1.05] -> entry 10 only.
  EXPECT_DOUBLE_EQ(alignedPreviousScoreInMetres(previous, odometers, 13, 0.3, 0.05), 1.3);
  // Window 0.12 m: [0.88, 1.12] -> entries 9..11, best 1.3.
  EXPECT_DOUBLE_EQ(alignedPreviousScoreInMetres(previous, odometers, 13, 0.3, 0.12), 1.3);
  // Eq. 7's tj-1 (entry 12) was not scored: the keyframe reading finds nothing.
  TemporalScoreOptions o;
  EXPECT_DOUBLE_EQ(alignedPreviousScore(previous, 13, 0, o), 0.0);
  // Stopped (driven 0): the same place, entry 14.
  EXPECT_DOUBLE_EQ(alignedPreviousScoreInMetres(previous, odometers, 14, 0.0, 0.05), 2.2);
  // Nothing scored near 0.3 m before entry 5 (0.2 m): 0.
  EXPECT_DOUBLE_EQ(alignedPreviousScoreInMetres(previous, odometers, 5, 0.3, 0.05), 0.0);
  EXPECT_THROW(alignedPreviousScoreInMetres(previous, odometers, 21, 0.3, 0.05),
               std::invalid_argument);
  EXPECT_THROW(alignedPreviousScoreInMetres(previous, odometers, 5, -0.1, 0.05),
               std::invalid_argument);
}

TEST(AlignedPreviousScoreInMetres, EntriesWithoutOdometerNeverMatch) {
  // Database::odometers() gives -inf before the first known odometer.
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> odometers{-inf, -inf, 0.0, 0.5, 1.0};
  const Scores previous{{0, 9.0}, {1, 9.0}, {3, 0.7}};
  EXPECT_DOUBLE_EQ(alignedPreviousScoreInMetres(previous, odometers, 4, 0.5, 0.1), 0.7);
  EXPECT_DOUBLE_EQ(alignedPreviousScoreInMetres(previous, odometers, 4, 1.0, 0.1), 0.0);
}

TEST(AlignedPreviousScores, WalksTheWindowsOfAscendingCandidatesByHand) {
  const Scores previous{{2, 0.5}, {5, 0.9}, {6, 0.3}};
  AlignedPreviousScores walk(previous, 0, window(1));
  EXPECT_DOUBLE_EQ(walk(0), 0.0);                // window [0, 0] (centre -1, clipped)
  EXPECT_DOUBLE_EQ(walk(4), 0.5);                // centre 3: [2, 4] holds entry 2
  EXPECT_DOUBLE_EQ(walk(4), 0.5);                // the same entry again
  EXPECT_DOUBLE_EQ(walk(7), 0.9);                // centre 6: [5, 7], best of 0.9 and 0.3
  EXPECT_DOUBLE_EQ(walk(9), 0.0);                // centre 8: [7, 9], nothing scored
  EXPECT_THROW(walk(8), std::invalid_argument);  // not ascending
  EXPECT_THROW(AlignedPreviousScores(previous, -1, window(1)), std::invalid_argument);

  // In metres: entries every 0.1 m, driven 0.3 m, window 0.12 m.
  std::vector<double> odometers;
  for (int i = 0; i <= 20; ++i) odometers.push_back(0.1 * i);
  const Scores scored{{8, 0.4}, {10, 1.3}, {11, 0.9}, {14, 2.2}};
  AlignedPreviousScores metres(scored, odometers, 0.3, 0.12);
  EXPECT_DOUBLE_EQ(metres(5), 0.0);   // [0.08, 0.32]: entries 1..3
  EXPECT_DOUBLE_EQ(metres(11), 0.4);  // [0.68, 0.92]: entries 7..9
  EXPECT_DOUBLE_EQ(metres(13), 1.3);  // [0.88, 1.12]: entries 9..11
  EXPECT_DOUBLE_EQ(metres(17), 2.2);  // [1.28, 1.52]: entries 13..15
  EXPECT_THROW(metres(21), std::invalid_argument);
  EXPECT_THROW(AlignedPreviousScores(scored, odometers, -0.1, 0.1), std::invalid_argument);
  EXPECT_THROW(AlignedPreviousScores(scored, odometers, 0.1, std::nan("")), std::invalid_argument);
}

// Walking the candidates of a query must give exactly what asking each one
// alone gives (the functions: fresh cursors, a search of the whole range),
// on random histories: gaps, repeated odometers, entries without odometer,
// candidates asked twice.
TEST(AlignedPreviousScores, WalkingEqualsAskingEachCandidateAloneOnRandomHistories) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 200; ++trial) {
    const EntryId n = 1 + rng() % 300;
    std::vector<double> odometers;
    double odometer = 0.0;
    const EntryId unknown = rng() % 4 == 0 ? rng() % 10 : 0;  // leading entries without odometer
    for (EntryId i = 0; i < n; ++i) {
      if (i < unknown) {
        odometers.push_back(-inf);
        continue;
      }
      if (rng() % 5 != 0) odometer += 0.2 * unit(rng);  // a fifth stand still
      odometers.push_back(odometer);
    }
    Scores previous;
    for (EntryId i = 0; i < n; ++i) {
      if (unit(rng) < 0.4) previous.emplace_back(i, unit(rng) * 3.0);
    }
    std::vector<EntryId> candidates;
    for (EntryId i = 0; i < n; ++i) {
      if (unit(rng) < 0.3) candidates.push_back(i);
      if (unit(rng) < 0.05) candidates.push_back(i);  // asked twice
    }
    const int missed = static_cast<int>(rng() % 3);
    const TemporalScoreOptions o = window(static_cast<int>(rng() % 4));
    const double driven = unit(rng) < 0.2 ? 0.0 : unit(rng);
    const double window_m = unit(rng) < 0.2 ? 0.0 : 0.3 * unit(rng);
    AlignedPreviousScores in_keyframes(previous, missed, o);
    AlignedPreviousScores in_metres(previous, odometers, driven, window_m);
    for (const EntryId c : candidates) {
      ASSERT_EQ(in_keyframes(c), alignedPreviousScore(previous, c, missed, o))
          << "trial " << trial << " entry " << c;
      ASSERT_EQ(in_metres(c),
                alignedPreviousScoreInMetres(previous, odometers, c, driven, window_m))
          << "trial " << trial << " entry " << c;
    }
  }
}

}  // namespace
}  // namespace bowg
