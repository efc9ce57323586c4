#include "bowg_evaluation/stamp_index.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace bowg {
namespace eval {
namespace {

// Frames 0..3 at 100, 200, 300, 300 ns (frame 3 repeats frame 2's stamp) and
// frame 4 at 150 ns (out of order).
StampIndex example() { return StampIndex({100, 200, 300, 300, 150}); }

TEST(StampIndex, ExactStampsMapToTheirFrameAndRepeatsToTheFirst) {
  const StampIndex index = example();
  EXPECT_EQ(index.frames(), 5u);
  EXPECT_EQ(index.find(100, 0), 0);
  EXPECT_EQ(index.find(200, 0), 1);
  EXPECT_EQ(index.find(300, 0), 2);  // not 3: the nodelet skips the repeat
  EXPECT_EQ(index.find(150, 0), 4);
  EXPECT_EQ(index.find(101, 0), -1);
}

TEST(StampIndex, NearestWithinTheTolerance) {
  const StampIndex index = example();
  // 170: |170-150| = 20, |170-200| = 30 -> frame 4 when tolerance >= 20.
  EXPECT_EQ(index.find(170, 20), 4);
  EXPECT_EQ(index.find(170, 19), -1);
  // 180: 30 from 150, 20 from 200 -> frame 1.
  EXPECT_EQ(index.find(180, 25), 1);
  // 125: 25 from 100 and from 150 -> the earlier stamp (frame 0).
  EXPECT_EQ(index.find(125, 25), 0);
  // Outside the range: 90 is 10 before the first, 310 10 after the last.
  EXPECT_EQ(index.find(90, 10), 0);
  EXPECT_EQ(index.find(310, 10), 2);
  EXPECT_EQ(index.find(311, 10), -1);
  EXPECT_THROW(index.find(100, -1), std::invalid_argument);
}

TEST(StampIndex, SafeToleranceIsBelowHalfTheSmallestGap) {
  // Distinct stamps 100, 150, 200, 300: smallest gap 50 -> (50 - 1) / 2 = 24.
  EXPECT_EQ(example().safeTolerance(1000), 24);
  EXPECT_EQ(example().safeTolerance(10), 10);  // the cap
  // With 24 ns no stamp is within reach of two frames: 125 is 25 from both.
  EXPECT_EQ(example().find(125, 24), -1);
  EXPECT_EQ(StampIndex({}).find(0, 100), -1);
  EXPECT_EQ(StampIndex({}).safeTolerance(7), 7);
}

TEST(StampIndex, EpochStampsSurviveTheDetectorsDoubleSeconds) {
  // 1700000000.123456789 s: as double seconds the nanoseconds are lost (the
  // spacing of doubles near 1.7e9 is 2^-22 s = 238 ns), the frame is found
  // again with a tolerance of 1 us.
  const std::int64_t stamp = 1700000000123456789LL;
  const StampIndex index({stamp - 100000000, stamp, stamp + 100000000});
  const double seconds = 1700000000.123456789;
  const std::int64_t back = secondsToNanoseconds(seconds);
  EXPECT_LE(std::abs(back - stamp), 238);
  EXPECT_EQ(index.find(back, 1000), 1);
  EXPECT_EQ(secondsToNanoseconds(1.5), 1500000000);
  EXPECT_THROW(secondsToNanoseconds(1e300), std::invalid_argument);
}

}  // namespace
}  // namespace eval
}  // namespace bowg
