#include "bowg_evaluation/timing_stats.h"

#include <gtest/gtest.h>

namespace bowg {
namespace eval {
namespace {

TEST(TimingStatsTest, OddCount) {
  // {5,1,3,2,4}: mean 15/5 = 3, median 3, p95 = ceil(4.75) = 5th smallest = 5.
  const TimingStats s = computeTimingStats({5, 1, 3, 2, 4});
  EXPECT_EQ(s.count, 5);
  EXPECT_DOUBLE_EQ(s.mean, 3);
  EXPECT_DOUBLE_EQ(s.median, 3);
  EXPECT_DOUBLE_EQ(s.p95, 5);
  EXPECT_DOUBLE_EQ(s.max, 5);
}

TEST(TimingStatsTest, EvenCountAndNearestRankPercentile) {
  // {1,2,3,4}: median (2+3)/2; p95 = ceil(3.8) = 4th = 4.
  const TimingStats s = computeTimingStats({4, 3, 2, 1});
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.p95, 4);
  // 1..20: p95 = ceil(19) = 19th smallest = 19, mean 10.5.
  std::vector<double> v;
  for (int i = 20; i >= 1; --i) v.push_back(i);
  const TimingStats t = computeTimingStats(v);
  EXPECT_DOUBLE_EQ(t.p95, 19);
  EXPECT_DOUBLE_EQ(t.mean, 10.5);
  EXPECT_DOUBLE_EQ(t.max, 20);
}

TEST(TimingStatsTest, EmptyIsAllZero) {
  const TimingStats s = computeTimingStats({});
  EXPECT_EQ(s.count, 0);
  EXPECT_DOUBLE_EQ(s.mean, 0);
  EXPECT_DOUBLE_EQ(s.max, 0);
}

}  // namespace
}  // namespace eval
}  // namespace bowg
