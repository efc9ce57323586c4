#include "bowg_pipe_sim/sequence_stats.h"

#include <gtest/gtest.h>

namespace bowg {
namespace pipe_sim {
namespace {

TEST(SequenceStatsTest, SpacingIsSignedAndDrivenIsTheOdometer) {
  std::vector<FrameState> frames(5);
  const double distance[] = {0, 0.02, 0.02, 0.01, 0.05};
  const double odometer[] = {0, 0.02, 0.02, 0.03, 0.07};
  for (int i = 0; i < 5; ++i) frames[i].distance = distance[i], frames[i].odometer = odometer[i];
  const SequenceStats s = sequenceStats(frames);
  EXPECT_EQ(s.frames, 5);
  EXPECT_DOUBLE_EQ(s.driven_m, 0.07);
  EXPECT_NEAR(s.spacing_min_m, -0.01, 1e-12);
  EXPECT_NEAR(s.spacing_max_m, 0.04, 1e-12);
  EXPECT_NEAR(s.spacing_median_m, 0.02, 1e-12);  // of -0.01, 0, 0.02, 0.04: upper median
  EXPECT_EQ(sequenceStats({}).frames, 0);
  EXPECT_EQ(sequenceStats(std::vector<FrameState>(1)).spacing_max_m, 0);
}

TEST(SequenceStatsTest, TheSpacingIsMeasuredWithinDrives) {
  // A second mission from frame 3: its route position starts at 0 again,
  // which is no step of -0.04 m; the odometer goes on.
  std::vector<FrameState> frames(5);
  const double distance[] = {0, 0.02, 0.04, 0, 0.01};
  const double odometer[] = {0, 0.02, 0.04, 0.04, 0.05};
  for (int i = 0; i < 5; ++i) frames[i].distance = distance[i], frames[i].odometer = odometer[i];
  const SequenceStats s = sequenceStats(frames, {3});
  EXPECT_DOUBLE_EQ(s.driven_m, 0.05);
  EXPECT_NEAR(s.spacing_min_m, 0.01, 1e-12);
  EXPECT_NEAR(s.spacing_max_m, 0.02, 1e-12);
  EXPECT_NEAR(sequenceStats(frames).spacing_min_m, -0.04, 1e-12);
}

TEST(SequenceStatsTest, MedianIsTheUpperMedian) {
  EXPECT_EQ(median({}), 0);
  EXPECT_EQ(median({3, 1, 2}), 2);
  EXPECT_EQ(median({4, 1, 3, 2}), 3);
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
