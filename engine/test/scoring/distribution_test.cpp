// Fan bins, distribution vectors and the cyclic-shift distribution score
// (paper Sec. III-C, reading of docs/method.md, step 5), worked out by hand.
#include "bowg/scoring/distribution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace bowg {
namespace {

const double kPi = 3.14159265358979323846;

Keypoint kp(double x, double y) {
  Keypoint k;
  k.x = static_cast<float>(x);
  k.y = static_cast<float>(y);
  return k;
}

// A point at `degrees` from the centre (cx, cy), radius r, image coordinates.
Keypoint polar(double cx, double cy, double degrees, double r = 50.0) {
  const double a = degrees * kPi / 180.0;
  return kp(cx + r * std::cos(a), cy + r * std::sin(a));
}

TEST(FanBin, OneBinHoldsEverything) {
  EXPECT_EQ(fanBin(10.f, 10.f, 0, 0, 1), 0);
  EXPECT_EQ(fanBin(-10.f, 3.f, 0, 0, 1), 0);
  EXPECT_EQ(fanBin(0.f, -7.f, 0, 0, 1), 0);
}

// The bin by its definition: atan2's angle in [0, 2 pi) over the bin width.
int definitionBin(float x, float y, double cx, double cy, int m) {
  const double dx = static_cast<double>(x) - cx, dy = static_cast<double>(y) - cy;
  if (dx == 0.0 && dy == 0.0) return 0;
  double angle = std::atan2(dy, dx);
  if (angle < 0.0) angle += 2.0 * kPi;
  const int k = static_cast<int>(std::floor(angle / (2.0 * kPi / m)));
  return k >= m ? m - 1 : k;
}

TEST(FanBin, IsAtan2sBinEverywhereAndAtTheEdges) {
  // fanBin takes the bin from an approximate angle away from the bins'
  // edges; it must give atan2's bin for every point: random points, and
  // points at each edge and at 0-100 urad on either side of it (the
  // approximation's margin is 10 urad).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-400.0, 400.0);
  const double cx = 320.25, cy = 239.75;
  const double offsets[] = {0.0,   1e-9,   -1e-9,   1e-7, -1e-7, 2e-6, -2e-6, 9e-6,
                            -9e-6, 1.1e-5, -1.1e-5, 2e-5, -2e-5, 1e-4, -1e-4};
  for (const int m : {1, 2, 3, 5, 7, 8, 12, 36, 360}) {
    for (int i = 0; i < 20000; ++i) {
      const float x = static_cast<float>(cx + u(rng)), y = static_cast<float>(cy + u(rng));
      ASSERT_EQ(fanBin(x, y, cx, cy, m), definitionBin(x, y, cx, cy, m))
          << "m " << m << " at (" << x << ", " << y << ")";
    }
    for (int k = 0; k < m; ++k) {
      for (const double offset : offsets) {
        for (const double r : {3.0, 150.0, 390.0}) {
          const double a = 2.0 * kPi * k / m + offset;
          const float x = static_cast<float>(cx + r * std::cos(a));
          const float y = static_cast<float>(cy + r * std::sin(a));
          ASSERT_EQ(fanBin(x, y, cx, cy, m), definitionBin(x, y, cx, cy, m))
              << "m " << m << " edge " << k << " offset " << offset << " radius " << r;
        }
      }
    }
  }
  // On the axes and diagonals exactly (float coordinates, integer centre).
  for (const int m : {4, 8}) {
    for (int dx = -2; dx <= 2; ++dx)
      for (int dy = -2; dy <= 2; ++dy)
        EXPECT_EQ(fanBin(100.f + dx, 50.f + dy, 100, 50, m),
                  definitionBin(100.f + dx, 50.f + dy, 100, 50, m))
            << dx << ", " << dy;
  }
}

TEST(FanBin, FourBinsInImageCoordinates) {
  // Centre (100, 100); y grows downwards, so atan2(dy, dx) turns clockwise on
  // screen. Bin width 90 degrees.
  //   (110, 105): atan2( 5,  10) =  26.6 deg            -> bin 0
  //   ( 95, 110): atan2(10,  -5) = 116.6 deg            -> bin 1
  //   ( 90,  95): atan2(-5, -10) = -153.4 -> 206.6 deg  -> bin 2
  //   (105,  90): atan2(-10,  5) =  -63.4 -> 296.6 deg  -> bin 3
  EXPECT_EQ(fanBin(110.f, 105.f, 100, 100, 4), 0);
  EXPECT_EQ(fanBin(95.f, 110.f, 100, 100, 4), 1);
  EXPECT_EQ(fanBin(90.f, 95.f, 100, 100, 4), 2);
  EXPECT_EQ(fanBin(105.f, 90.f, 100, 100, 4), 3);
}

TEST(FanBin, BinStartsBelongToTheirBin) {
  // Bin k starts at 2*pi*k/m: the four axis directions open bins 0..3.
  EXPECT_EQ(fanBin(110.f, 100.f, 100, 100, 4), 0);  // 0
  EXPECT_EQ(fanBin(100.f, 110.f, 100, 100, 4), 1);  // pi/2 (straight down)
  EXPECT_EQ(fanBin(90.f, 100.f, 100, 100, 4), 2);   // pi
  EXPECT_EQ(fanBin(100.f, 90.f, 100, 100, 4), 3);   // -pi/2 -> 3*pi/2
}

TEST(FanBin, EightBinsAtBinCentres) {
  // 22.5 + 45 k degrees lies in the middle of bin k.
  for (int k = 0; k < 8; ++k) {
    const Keypoint p = polar(320, 240, 22.5 + 45.0 * k);
    EXPECT_EQ(fanBin(p.x, p.y, 320, 240, 8), k) << "bin " << k;
  }
  // Just either side of the 45-degree boundary.
  const Keypoint a = polar(320, 240, 44.0), b = polar(320, 240, 46.0);
  EXPECT_EQ(fanBin(a.x, a.y, 320, 240, 8), 0);
  EXPECT_EQ(fanBin(b.x, b.y, 320, 240, 8), 1);
  // Just below 360 degrees is the last bin, not bin 8.
  const Keypoint c = polar(320, 240, 359.9);
  EXPECT_EQ(fanBin(c.x, c.y, 320, 240, 8), 7);
}

TEST(FanBin, CentreGoesToBinZero) { EXPECT_EQ(fanBin(5.f, 7.f, 5.0, 7.0, 8), 0); }

TEST(FanBin, BadInputThrows) {
  EXPECT_THROW(fanBin(1.f, 1.f, 0, 0, 0), std::invalid_argument);
  EXPECT_THROW(fanBin(1.f, 1.f, 0, 0, -3), std::invalid_argument);
  EXPECT_THROW(fanBin(std::numeric_limits<float>::quiet_NaN(), 1.f, 0, 0, 4),
               std::invalid_argument);
  EXPECT_THROW(fanBin(1.f, 1.f, std::numeric_limits<double>::infinity(), 0, 4),
               std::invalid_argument);
}

TEST(DistributionVector, CountsAreL2Normalised) {
  // m = 4 around (0, 0): 3 points in bin 0, 4 in bin 1 -> (3, 4, 0, 0) / 5.
  std::vector<Keypoint> kps;
  for (int i = 0; i < 3; ++i) kps.push_back(polar(0, 0, 10.0 + 20.0 * i));
  for (int i = 0; i < 4; ++i) kps.push_back(polar(0, 0, 95.0 + 20.0 * i));
  const std::vector<double> v = distributionVector(imagePoints(kps), 0, 0, 4);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_DOUBLE_EQ(v[0], 0.6);
  EXPECT_DOUBLE_EQ(v[1], 0.8);
  EXPECT_DOUBLE_EQ(v[2], 0.0);
  EXPECT_DOUBLE_EQ(v[3], 0.0);
}

TEST(DistributionVector, NoKeypointsGivesZeros) {
  const std::vector<double> v = distributionVector({}, 10, 10, 8);
  EXPECT_EQ(v, std::vector<double>(8, 0.0));
  EXPECT_THROW(distributionVector({}, 10, 10, 0), std::invalid_argument);
}

TEST(DistributionScore, IdenticalVectorsScoreOne) {
  const std::vector<double> v{0.6, 0.8, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(distributionScore(v, v), 1.0);
}

TEST(DistributionScore, ShiftByTwoBinsScoresOne) {
  // Roll invariance: q = (0, 0, 0.6, 0.8) is v shifted by two bins; column
  // M_2 of q's matrix is (q2, q3, q0, q1) = v, so the score is <v, v> = 1.
  const std::vector<double> v{0.6, 0.8, 0.0, 0.0};
  const std::vector<double> q{0.0, 0.0, 0.6, 0.8};
  EXPECT_NEAR(distributionScore(q, v), 1.0, 1e-12);
  EXPECT_NEAR(distributionScore(v, q), 1.0, 1e-12);
}

TEST(DistributionScore, BestShiftOfTwoDifferentVectors) {
  // q = (0.6, 0.8, 0, 0), db = (0.8, 0, 0.6, 0); M_i = (q_i, q_i+1, q_i+2, q_i+3):
  //   i = 0: (0.6, 0.8, 0,   0  ) . db = 0.48
  //   i = 1: (0.8, 0,   0,   0.6) . db = 0.64
  //   i = 2: (0,   0,   0.6, 0.8) . db = 0.36
  //   i = 3: (0,   0.6, 0.8, 0  ) . db = 0.48
  // max = 0.64.
  const std::vector<double> q{0.6, 0.8, 0.0, 0.0};
  const std::vector<double> db{0.8, 0.0, 0.6, 0.0};
  EXPECT_NEAR(distributionScore(q, db), 0.64, 1e-12);
}

TEST(DistributionScore, RolledKeypointsScoreOne) {
  // Keypoints rotated about the centre by two 45-degree bins (a camera roll)
  // give the same vector shifted by two: the score stays 1, while the
  // unshifted inner product is lower. Angles lie well inside their bins.
  const double offsets[] = {5, 12, 20, 33, 40, 8, 27};
  const int bins[] = {0, 0, 1, 3, 3, 3, 6};
  std::vector<Keypoint> kps, rolled;
  for (int i = 0; i < 7; ++i) {
    const double deg = 45.0 * bins[i] + offsets[i];
    kps.push_back(polar(320, 240, deg));
    rolled.push_back(polar(320, 240, deg + 90.0));
  }
  const std::vector<double> v = distributionVector(imagePoints(kps), 320, 240, 8);
  const std::vector<double> w = distributionVector(imagePoints(rolled), 320, 240, 8);
  EXPECT_NEAR(distributionScore(v, w), 1.0, 1e-12);
  double unshifted = 0.0;
  for (int j = 0; j < 8; ++j) unshifted += v[j] * w[j];
  EXPECT_LT(unshifted, 0.9);
}

TEST(DistributionScore, ZeroVectorScoresZero) {
  EXPECT_DOUBLE_EQ(distributionScore(std::vector<double>(4, 0.0), {0.6, 0.8, 0.0, 0.0}), 0.0);
}

TEST(DistributionScore, SizeMismatchThrows) {
  EXPECT_THROW(distributionScore({1.0, 0.0}, {1.0, 0.0, 0.0}), std::invalid_argument);
}

TEST(DistributionScore, EveryAlignmentSummedInTheOrderOfTheDefinition) {
  // The definition, one alignment at a time: max_i sum_j v_((i+j) mod m) w_j,
  // j ascending. The score must be that, bit for bit, for any m and any
  // vectors.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t m = 1; m <= 70; ++m) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> q(m), w(m);
      for (std::size_t i = 0; i < m; ++i) {
        q[i] = trial % 4 == 0 && i % 3 == 0 ? 0.0 : u(rng);
        w[i] = u(rng) / static_cast<double>(m);
      }
      double best = 0.0;
      for (std::size_t i = 0; i < m; ++i) {
        double dot = 0.0;
        for (std::size_t j = 0; j < m; ++j) dot += q[(i + j) % m] * w[j];
        if (dot > best) best = dot;
      }
      ASSERT_EQ(distributionScore(q, w), best > 1.0 ? 1.0 : best) << "m " << m;
    }
  }
  EXPECT_DOUBLE_EQ(distributionScore({}, {}), 0.0);
}

TEST(DistributionScorer, OneQueryScoresManyVectorsAsDistributionScoreDoes) {
  // A database query scores every entry it reaches with one scorer: each
  // score must be distributionScore's, bit for bit, whatever came before
  // (the shifts' sums are reset per vector). The hand case first: the
  // worked example of BestShiftOfTwoDifferentVectors (0.64), then its
  // query against itself (1) and against a vector of one bin (0.8: the
  // best shift puts the query's 0.8 on it).
  const std::vector<double> q{0.6, 0.8, 0.0, 0.0};
  DistributionScorer scorer(q, 4, "test");
  ASSERT_EQ(scorer.bins(), 4u);
  const double db[] = {0.8, 0.0, 0.6, 0.0};
  const double one_bin[] = {0.0, 0.0, 1.0, 0.0};
  EXPECT_NEAR(scorer.score(db), 0.64, 1e-12);
  EXPECT_DOUBLE_EQ(scorer.score(q.data()), 1.0);
  EXPECT_NEAR(scorer.score(one_bin), 0.8, 1e-12);
  EXPECT_NEAR(scorer.score(db), 0.64, 1e-12);

  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t m : {1u, 8u, 13u, 70u}) {
    std::vector<double> query(m);
    for (double& v : query) v = u(rng);
    DistributionScorer many(query, m, "test");
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<double> w(m);
      for (double& v : w) v = u(rng) / static_cast<double>(m);
      ASSERT_EQ(many.score(w.data()), distributionScore(query, w)) << "m " << m;
    }
  }
  DistributionScorer empty({}, 0, "test");
  EXPECT_DOUBLE_EQ(empty.score(nullptr), 0.0);
  const DistributionScorer none;  // a query without distribution score
  EXPECT_EQ(none.bins(), 0u);
  // A vector of another bin count is refused by name, before any score.
  try {
    DistributionScorer(q, 8, "Database::query");
    FAIL() << "a query of 4 bins against vectors of 8 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("Database::query"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("4 bins"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bowg
