// Islands (paper Sec. III-D, eq. 10) on hand-made candidate lists. The
// temporal verification: temporal_consistency_test.cpp.
#include "bowg/detection/islands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "bowg/core/errors.h"

namespace bowg {
namespace {

using Candidates = std::vector<std::pair<EntryId, double>>;

// min_score 0.3, gap 3, min size 1 (the defaults, spelled out).
IslandOptions islandOptions() {
  IslandOptions o;
  o.min_score = 0.3;
  o.max_intra_island_gap = 3;
  o.min_island_size = 1;
  return o;
}

// After dropping entry 8 (0.2 < 0.3):
//   5 (0.5), 6 (0.4), 9 (0.6): gaps 1 and 3 <= 3  -> [5, 9]  H = 1.5, best 9
//   20 (0.9): gap 11                               -> [20,20] H = 0.9
//   30 (0.35), 31 (0.35), 33 (0.4): gaps 1, 2      -> [30,33] H = 1.1, best 33
Candidates handCandidates() {
  return {{20, 0.9}, {5, 0.5}, {31, 0.35}, {8, 0.2}, {6, 0.4}, {33, 0.4}, {9, 0.6}, {30, 0.35}};
}

void expectIsland(const Island& i, EntryId first, EntryId last, double score, EntryId best,
                  double best_score, int size) {
  EXPECT_EQ(i.first, first);
  EXPECT_EQ(i.last, last);
  EXPECT_NEAR(i.score, score, 1e-12);
  EXPECT_EQ(i.best_entry, best);
  EXPECT_DOUBLE_EQ(i.best_score, best_score);
  EXPECT_EQ(i.size, size);
}

TEST(IslandOptionsFor, ImagesOnlyAddsTheMargin) {
  IslandOptions o;
  o.min_score = 1.0;
  o.images_only_score_margin = 0.1;
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kPositions).min_score, 1.0);
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kOdometer).min_score, 1.0);
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kNone).min_score, 1.1);
  o.images_only_score_margin = 0.0;
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kNone).min_score, 1.0);
  o.images_only_score_margin = -0.1;
  EXPECT_THROW(o.validate(), std::exception);
}

TEST(IslandOptionsFor, OdometerOnlyUsesItsOwnExclusionWindow) {
  IslandOptions o;
  o.recent_exclusion_m = 2.0;
  o.recent_exclusion_odometer_m = 5.0;
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kOdometer).recent_exclusion_m, 5.0);
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kPositions).recent_exclusion_m, 2.0);
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kNone).recent_exclusion_m, 2.0);
  // 0 = the odometer-only query keeps recent_exclusion_m.
  o.recent_exclusion_odometer_m = 0.0;
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kOdometer).recent_exclusion_m, 2.0);
  // The margin is the images-only query's alone.
  o.images_only_score_margin = 0.3;
  EXPECT_DOUBLE_EQ(islandOptionsFor(o, OdometryInput::kOdometer).min_score, o.min_score);
}

TEST(ComputeIslands, HandMadeCandidates) {
  const std::vector<Island> islands = computeIslands(handCandidates(), islandOptions());
  ASSERT_EQ(islands.size(), 3u);
  // Sorted by score: 1.5 > 1.1 > 0.9. Entry 8 is below the threshold, so it
  // adds nothing to [5, 9] (H would be 1.7 otherwise).
  expectIsland(islands[0], 5, 9, 1.5, 9, 0.6, 3);
  expectIsland(islands[1], 30, 33, 1.1, 33, 0.4, 3);
  expectIsland(islands[2], 20, 20, 0.9, 20, 0.9, 1);
}

TEST(ComputeIslands, InputOrderDoesNotMatter) {
  Candidates c = handCandidates();
  std::mt19937 rng(7);
  for (int round = 0; round < 5; ++round) {
    std::shuffle(c.begin(), c.end(), rng);
    const std::vector<Island> islands = computeIslands(c, islandOptions());
    ASSERT_EQ(islands.size(), 3u);
    expectIsland(islands[0], 5, 9, 1.5, 9, 0.6, 3);
  }
}

TEST(ComputeIslands, MinIslandSizeDropsSmallIslands) {
  IslandOptions o = islandOptions();
  o.min_island_size = 2;
  const std::vector<Island> islands = computeIslands(handCandidates(), o);
  ASSERT_EQ(islands.size(), 2u);
  expectIsland(islands[0], 5, 9, 1.5, 9, 0.6, 3);
  expectIsland(islands[1], 30, 33, 1.1, 33, 0.4, 3);
  o.min_island_size = 4;
  EXPECT_TRUE(computeIslands(handCandidates(), o).empty());
}

TEST(ComputeIslands, ThresholdSplitsIslands) {
  // min_score 0.5 keeps 5 (0.5, >= is kept), 9 (0.6) and 20 (0.9). Without 6
  // the gap 5 -> 9 is 4 > 3: three singletons, best first.
  IslandOptions o = islandOptions();
  o.min_score = 0.5;
  const std::vector<Island> islands = computeIslands(handCandidates(), o);
  ASSERT_EQ(islands.size(), 3u);
  expectIsland(islands[0], 20, 20, 0.9, 20, 0.9, 1);
  expectIsland(islands[1], 9, 9, 0.6, 9, 0.6, 1);
  expectIsland(islands[2], 5, 5, 0.5, 5, 0.5, 1);
  o.min_score = 0.95;
  EXPECT_TRUE(computeIslands(handCandidates(), o).empty());
}

TEST(ComputeIslands, GapIsInclusive) {
  // Ids 10 and 12 differ by 2: one island for gap 2, two for gap 1.
  const Candidates c{{10, 0.5}, {12, 0.5}};
  IslandOptions o = islandOptions();
  o.max_intra_island_gap = 2;
  EXPECT_EQ(computeIslands(c, o).size(), 1u);
  o.max_intra_island_gap = 1;
  EXPECT_EQ(computeIslands(c, o).size(), 2u);
  o.max_intra_island_gap = 0;  // every entry alone, even consecutive ones
  EXPECT_EQ(computeIslands({{10, 0.5}, {11, 0.5}}, o).size(), 2u);
}

TEST(ComputeIslands, TiesGoToTheMoreRecent) {
  // Two islands with H = 0.8: [40, 41] before [10, 11]. Inside [40, 41] both
  // members score 0.4: best entry 41.
  const std::vector<Island> islands =
      computeIslands({{10, 0.4}, {11, 0.4}, {40, 0.4}, {41, 0.4}}, islandOptions());
  ASSERT_EQ(islands.size(), 2u);
  EXPECT_EQ(islands[0].first, 40u);
  EXPECT_EQ(islands[0].best_entry, 41u);
  EXPECT_EQ(islands[1].first, 10u);
}

TEST(ComputeIslands, EmptyAndInvalidInput) {
  EXPECT_TRUE(computeIslands({}, islandOptions()).empty());
  EXPECT_THROW(computeIslands({{3, 0.5}, {3, 0.6}}, islandOptions()), std::invalid_argument);
  IslandOptions bad = islandOptions();
  bad.min_island_size = 0;
  EXPECT_THROW(computeIslands(handCandidates(), bad), InvalidParameter);
}

}  // namespace
}  // namespace bowg
