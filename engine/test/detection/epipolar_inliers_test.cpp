// The inlier count of RANSAC's inner loop: a hand-worked model (pure
// horizontal motion: the epipolar lines are the rows, a pair's distance is
// its vertical offset), and every version (scalar, SSE2, AVX2 where the CPU
// has it) against the per-pair test of fundamental_matrix.h on random
// models and 0-41 pairs, with and without giving up early.
#include "detection/epipolar_inliers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "bowg/detection/fundamental_matrix.h"
#include "core/cpu_features.h"

namespace bowg {
namespace {

using epipolar_inliers::CountInliers;
using epipolar_inliers::PairArrays;

struct Columns {
  std::vector<double> x1, y1, x2, y2;
  explicit Columns(const std::vector<PointPair>& pairs) {
    for (const PointPair& p : pairs) {
      x1.push_back(p.x1);
      y1.push_back(p.y1);
      x2.push_back(p.x2);
      y2.push_back(p.y2);
    }
  }
  PairArrays arrays() const { return PairArrays{x1.data(), y1.data(), x2.data(), y2.data()}; }
  std::uint32_t size() const { return static_cast<std::uint32_t>(x1.size()); }
};

std::vector<CountInliers> counts() {
  std::vector<CountInliers> c{epipolar_inliers::countInliersPortable};
  if (cpuHasAvx2()) c.push_back(epipolar_inliers::countInliersAvx2);
  return c;
}

// F = [0 0 0; 0 0 -1; 0 1 0]: x2^T F x1 = y1 - y2; both lines have gradient
// norm 1, so a pair is an inlier when its vertical offset is at most t.
const double kRows[9] = {0, 0, 0, 0, 0, -1, 0, 1, 0};

TEST(EpipolarInliers, VerticalOffsetsAgainstRowsByHand) {
  // Offsets 0, 0.5, ..., 3.0 (7 pairs): within t = 2 are 0 .. 2.0, the last
  // exactly at the threshold (4 <= 4): 5 inliers.
  std::vector<PointPair> pairs;
  for (int i = 0; i <= 6; ++i) pairs.push_back({10.0 * i, 100.0, 10.0 * i + 7.0, 100.0 + 0.5 * i});
  const Columns c(pairs);
  for (const CountInliers count : counts()) {
    EXPECT_EQ(count(c.arrays(), c.size(), kRows, 4.0, -1), 5);
    EXPECT_EQ(count(c.arrays(), c.size(), kRows, 0.0, -1), 1);  // only the offset 0
    EXPECT_EQ(count(c.arrays(), 0, kRows, 4.0, -1), 0);
  }
  EXPECT_EQ(epipolar_inliers::countInliersScalar(c.arrays(), kRows, 4.0, 0, 7), 5);
  EXPECT_EQ(epipolar_inliers::countInliersScalar(c.arrays(), kRows, 4.0, 2, 5), 3);
}

TEST(EpipolarInliers, UndefinedLinesAndNaNsAreNoInliers) {
  // The zero model has no line at all (normal 0); a NaN coordinate fails
  // every compare.
  const double zero[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<PointPair> pairs{{1, 2, 1, 2}, {3, 4, 3, 4}, {nan, 1, 2, 3}, {5, 6, 5, nan},
                                     {7, 8, 7, 8}, {9, 9, 9, 9}};
  const Columns c(pairs);
  for (const CountInliers count : counts()) {
    EXPECT_EQ(count(c.arrays(), c.size(), zero, 4.0, -1), 0);
    EXPECT_EQ(count(c.arrays(), c.size(), kRows, 4.0, -1), 4);
  }
}

TEST(EpipolarInliers, EveryVersionCountsWhatThePairTestAccepts) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> px(0, 640), py(0, 480), entry(-1, 1);
  for (int trial = 0; trial < 400; ++trial) {
    const std::uint32_t n = static_cast<std::uint32_t>(trial % 42);
    // Pairs near the rows' model (offsets around the threshold) and a
    // random model scaled like a pixel F.
    std::vector<PointPair> pairs;
    for (std::uint32_t i = 0; i < n; ++i) {
      const double x = px(rng), y = py(rng);
      pairs.push_back({x, y, x + 20 * entry(rng), y + 3 * entry(rng)});
    }
    double f[9];
    if (trial % 2 == 0) {
      for (int k = 0; k < 9; ++k) f[k] = kRows[k] + 1e-4 * entry(rng);
    } else {
      for (int k = 0; k < 9; ++k) f[k] = entry(rng) * (k < 6 ? 1e-5 : 1e-2);
    }
    const double t2 = 1.0 + 3.0 * (trial % 3);
    int expected = 0;
    for (const PointPair& p : pairs) {
      const EpipolarResidual e = epipolarResidual(f, p);
      expected += e.normal > 0.0 && e.residual * e.residual <= t2 * e.normal ? 1 : 0;
    }
    const Columns c(pairs);
    EXPECT_EQ(epipolar_inliers::countInliersScalar(c.arrays(), f, t2, 0, n), expected);
    for (const CountInliers count : counts()) {
      ASSERT_EQ(count(c.arrays(), n, f, t2, -1), expected) << "trial " << trial;
      // Giving up early: never more than `best` then, and the exact count
      // whenever it beats `best`.
      for (int best = 0; best <= static_cast<int>(n); best += 3) {
        const int got = count(c.arrays(), n, f, t2, best);
        if (expected > best) {
          EXPECT_EQ(got, expected) << "trial " << trial << " best " << best;
        } else {
          EXPECT_LE(got, best) << "trial " << trial << " best " << best;
        }
      }
    }
  }
}

TEST(EpipolarInliers, TheBestCountIsTheFastestTheCpuRuns) {
  EXPECT_EQ(epipolar_inliers::bestCountInliers(), cpuHasAvx2()
                                                      ? epipolar_inliers::countInliersAvx2
                                                      : epipolar_inliers::countInliersPortable);
}

}  // namespace
}  // namespace bowg
