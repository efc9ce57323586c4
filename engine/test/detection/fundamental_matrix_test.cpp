// The fundamental matrix's equations: the epipolar distance on hand-worked
// pairs and the 7-point solution on a known geometry.
#include "bowg/detection/fundamental_matrix.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace bowg {
namespace {

// F of two views related by a translation along x (normalised cameras,
// R = I, t = (1, 0, 0)): F = [t]x = [0 0 0; 0 0 -1; 0 1 0], so
// x2^T F x1 = y1 - y2 and a pair is on its epipolar lines iff y1 = y2.
const double kTranslationX[9] = {0, 0, 0, 0, 0, -1, 0, 1, 0};

TEST(FundamentalMatrix, EpipolarErrorOfHandWorkedPairs) {
  // On the lines: y1 = y2.
  EXPECT_DOUBLE_EQ(epipolarErrorSquared(kTranslationX, {3, 2, 5, 2}), 0.0);
  // y1 = 2, y2 = 5: the line F x1 = (0, -1, 2) is y = 2 in image 2 (distance
  // 3), F^T x2 = (0, 1, -5) is y = 5 in image 1 (distance 3): 9.
  EXPECT_DOUBLE_EQ(epipolarErrorSquared(kTranslationX, {3, 2, 5, 5}), 9.0);
  // F = [0 0 0; 0 0 -1; 0 2 0]: F x1 = (0, -1, 2 y1), the line y = 2 y1 in
  // image 2; F^T x2 = (0, 2, -y2), the line y = y2 / 2 in image 1. For
  // y1 = 2, y2 = 5: |5 - 4| = 1 in image 2, |2 - 2.5| = 0.5 in image 1;
  // the larger squared distance is image 2's 1.
  const double f2[9] = {0, 0, 0, 0, 0, -1, 0, 2, 0};
  EXPECT_DOUBLE_EQ(epipolarErrorSquared(f2, {3, 2, 5, 5}), 1.0);
  // F = [0 0 0; 0 0 -2; 0 1 0]: the line -2 y + y1 = 0 in image 2 and
  // y = 2 y2 in image 1. For y1 = 2, y2 = 1.5: |3 - 2| / 2 = 0.5 in image 2,
  // |2 - 3| = 1 in image 1: image 1's 1 is the larger.
  const double f3[9] = {0, 0, 0, 0, 0, -2, 0, 1, 0};
  EXPECT_DOUBLE_EQ(epipolarErrorSquared(f3, {3, 2, 5, 1.5}), 1.0);
  // The error does not depend on F's scale.
  const double f3x[9] = {0, 0, 0, 0, 0, -8, 0, 4, 0};
  EXPECT_DOUBLE_EQ(epipolarErrorSquared(f3x, {3, 2, 5, 1.5}), 1.0);
  // No line: F = 0.
  const double zero[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(epipolarErrorSquared(zero, {3, 2, 5, 1.5}), std::numeric_limits<double>::infinity());
}

TEST(FundamentalMatrix, SevenPointsOfATranslationAlongXGiveItsMatrix) {
  // Seven pairs with y1 = y2 and unrelated x: [t]x is a solution (rank 2).
  const PointPair pairs[7] = {{-1.0, 0.3, 0.2, 0.3}, {0.5, -0.7, 1.4, -0.7},
                              {1.2, 1.1, -0.3, 1.1}, {-0.4, -1.3, -1.1, -1.3},
                              {0.9, 0.6, 0.1, 0.6},  {-1.5, -0.2, 0.8, -0.2},
                              {0.2, 1.6, -1.7, 1.6}};
  double solutions[3][9];
  const int n = sevenPointFundamental(pairs, solutions);
  ASSERT_GE(n, 1);
  bool found = false;
  for (int s = 0; s < n; ++s) {
    // Scaled to a largest magnitude of 1: +-[t]x.
    const double sign = solutions[s][7] > 0 ? 1.0 : -1.0;
    double diff = 0;
    for (int j = 0; j < 9; ++j)
      diff = std::max(diff, std::fabs(sign * solutions[s][j] - kTranslationX[j]));
    found = found || diff < 1e-9;
  }
  EXPECT_TRUE(found);
}

double det3(const double m[9]) {
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
         m[2] * (m[3] * m[7] - m[4] * m[6]);
}

TEST(FundamentalMatrix, EverySevenPointSolutionIsSingularAndFitsItsSample) {
  // Random scenes: each solution has det F = 0 and puts the 7 pairs on
  // their epipolar lines; one of them is the true F (a rotation about y and
  // a translation, normalised cameras): F = [t]x R.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1), uz(3, 8);
  for (int trial = 0; trial < 50; ++trial) {
    const double a = 0.2 * u(rng), c = std::cos(a), s = std::sin(a);
    const double R[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
    const double t[3] = {u(rng), 0.3 * u(rng), 0.2 * u(rng)};
    const double tx[9] = {0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0};
    double truth[9];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k)
        truth[3 * r + k] = tx[3 * r] * R[k] + tx[3 * r + 1] * R[3 + k] + tx[3 * r + 2] * R[6 + k];
    PointPair pairs[7];
    for (auto& p : pairs) {
      const double X[3] = {u(rng), u(rng), uz(rng)};
      double Y[3];  // X in camera 2: R X + t
      for (int r = 0; r < 3; ++r)
        Y[r] = R[3 * r] * X[0] + R[3 * r + 1] * X[1] + R[3 * r + 2] * X[2] + t[r];
      p = {X[0] / X[2], X[1] / X[2], Y[0] / Y[2], Y[1] / Y[2]};
    }
    double solutions[3][9];
    const int n = sevenPointFundamental(pairs, solutions);
    ASSERT_GE(n, 1) << trial;
    double closest = 1e9;
    for (int m = 0; m < n; ++m) {
      EXPECT_NEAR(det3(solutions[m]), 0.0, 1e-9) << trial;
      for (const PointPair& p : pairs) EXPECT_LT(epipolarErrorSquared(solutions[m], p), 1e-16);
      // Distance to the truth up to scale and sign.
      double scale = 0;
      for (double v : truth) scale = std::max(scale, std::fabs(v));
      for (double sign : {-1.0, 1.0}) {
        double diff = 0;
        for (int j = 0; j < 9; ++j)
          diff = std::max(diff, std::fabs(sign * solutions[m][j] - truth[j] / scale));
        closest = std::min(closest, diff);
      }
    }
    EXPECT_LT(closest, 1e-6) << trial;
  }
}

TEST(FundamentalMatrix, EightPointsOfATranslationAlongXGiveItsMatrix) {
  // Ten pairs with y1 = y2: the least-squares F is +-[t]x exactly.
  PointPair pairs[10];
  for (int i = 0; i < 10; ++i) {
    const double y = -1.0 + 0.23 * i;
    pairs[i] = {std::sin(1.7 * i), y, std::cos(2.3 * i), y};
  }
  double f[9];
  ASSERT_TRUE(eightPointFundamental(pairs, 10, f));
  const double sign = f[7] > 0 ? 1.0 : -1.0;
  for (int j = 0; j < 9; ++j) EXPECT_NEAR(sign * f[j], kTranslationX[j], 1e-9) << j;
  // Fewer than 8 pairs do not determine it.
  EXPECT_FALSE(eightPointFundamental(pairs, 7, f));
}

TEST(FundamentalMatrix, EightPointFitIsRankTwoAndAveragesNoise) {
  // 100 noisy pairs of a known geometry: the fit is singular and its
  // epipolar errors stay at the noise's level (0.001 in these units).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), uz(3, 8);
  std::normal_distribution<double> noise(0, 0.001);
  const double a = 0.1, c = std::cos(a), s = std::sin(a);
  const double R[9] = {c, 0, s, 0, 1, 0, -s, 0, c};
  const double t[3] = {0.8, 0.1, 0.2};
  std::vector<PointPair> pairs;
  for (int i = 0; i < 100; ++i) {
    const double X[3] = {u(rng), u(rng), uz(rng)};
    double Y[3];
    for (int r = 0; r < 3; ++r)
      Y[r] = R[3 * r] * X[0] + R[3 * r + 1] * X[1] + R[3 * r + 2] * X[2] + t[r];
    pairs.push_back({X[0] / X[2] + noise(rng), X[1] / X[2] + noise(rng), Y[0] / Y[2] + noise(rng),
                     Y[1] / Y[2] + noise(rng)});
  }
  double f[9];
  ASSERT_TRUE(eightPointFundamental(pairs.data(), 100, f));
  EXPECT_NEAR(det3(f), 0.0, 1e-12);
  double mean = 0;
  for (const PointPair& p : pairs) mean += epipolarErrorSquared(f, p) / 100;
  EXPECT_LT(std::sqrt(mean), 0.003);
}

// The 7-point solutions of pairs that do not move: at least one, each
// skew-symmetric, singular, and fitting the pairs and `other` (a pair that
// does not move either) exactly.
void expectSkewSymmetricSolutions(const PointPair pairs[7], const PointPair& other) {
  double solutions[3][9];
  const int n = sevenPointFundamental(pairs, solutions);
  ASSERT_GE(n, 1);
  for (int s = 0; s < n; ++s) {
    const double* f = solutions[s];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(f[3 * i + j], -f[3 * j + i], 1e-12);
    EXPECT_NEAR(det3(f), 0.0, 1e-12);
    for (int i = 0; i < 7; ++i) EXPECT_LT(epipolarErrorSquared(f, pairs[i]), 1e-20);
    EXPECT_LT(epipolarErrorSquared(f, other), 1e-20);
  }
}

TEST(FundamentalMatrix, PairsThatDoNotMoveFitASkewSymmetricMatrix) {
  // x1 = x2: x^T F x = 0 for every skew-symmetric F, a three-dimensional
  // null space (rank 6). Each solution fits the pairs exactly, any pair
  // that does not move too, and is singular.
  const PointPair pairs[7] = {{-1.0, 0.3, -1.0, 0.3}, {0.5, -0.7, 0.5, -0.7},
                              {1.2, 1.1, 1.2, 1.1},   {-0.4, -1.3, -0.4, -1.3},
                              {0.9, 0.6, 0.9, 0.6},   {-1.5, -0.2, -1.5, -0.2},
                              {0.2, 1.6, 0.2, 1.6}};
  expectSkewSymmetricSolutions(pairs, {0.3, -0.8, 0.3, -0.8});
}

TEST(FundamentalMatrix, ARepeatedPairAmongPairsThatDoNotMoveIsSetAside) {
  // Row 2 repeats row 0: the elimination finds no pivot in it (after row 0
  // it is zero), moves it last and goes on with rows 3-6; the six distinct
  // pairs that do not move leave the skew-symmetric null space of rank 6.
  const PointPair pairs[7] = {{-1.0, 0.3, -1.0, 0.3}, {0.5, -0.7, 0.5, -0.7},
                              {-1.0, 0.3, -1.0, 0.3}, {-0.4, -1.3, -0.4, -1.3},
                              {0.9, 0.6, 0.9, 0.6},   {-1.5, -0.2, -1.5, -0.2},
                              {0.2, 1.6, 0.2, 1.6}};
  expectSkewSymmetricSolutions(pairs, {1.2, 1.1, 1.2, 1.1});
}

TEST(FundamentalMatrix, ADegenerateSampleHasNoSolution) {
  // Seven copies of one pair: the system has rank 1.
  PointPair pairs[7];
  for (auto& p : pairs) p = {0.1, 0.2, 0.3, 0.4};
  double solutions[3][9];
  EXPECT_EQ(sevenPointFundamental(pairs, solutions), 0);
  // Not finite.
  pairs[3].x1 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(sevenPointFundamental(pairs, solutions), 0);
}

}  // namespace
}  // namespace bowg
