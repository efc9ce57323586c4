// Hand-worked values for every word-score metric (see comments per case).
#include <cmath>

#include <gtest/gtest.h>

#include "bowg/vocabulary/bow_vector.h"

namespace bowg {
namespace {

// a = {1: 0.5, 2: 0.5}, b = {2: 0.25, 3: 0.75}: both L1-unit already.
BowVector A() { return {{1, 0.5}, {2, 0.5}}; }
BowVector B() { return {{2, 0.25}, {3, 0.75}}; }

TEST(BowVector, L1NormaliseScalesToUnitSum) {
  BowVector v{{1, 2.0}, {4, 6.0}};
  normaliseBowVector(ScoringType::kL1, &v);
  EXPECT_DOUBLE_EQ(v[0].second, 0.25);
  EXPECT_DOUBLE_EQ(v[1].second, 0.75);
}

TEST(BowVector, L2NormaliseScalesToUnitLength) {
  BowVector v{{1, 3.0}, {4, 4.0}};
  normaliseBowVector(ScoringType::kL2, &v);
  EXPECT_DOUBLE_EQ(v[0].second, 0.6);
  EXPECT_DOUBLE_EQ(v[1].second, 0.8);
}

TEST(BowVector, DotProductIsNotNormalised) {
  BowVector v{{1, 3.0}};
  normaliseBowVector(ScoringType::kDotProduct, &v);
  EXPECT_DOUBLE_EQ(v[0].second, 3.0);
}

TEST(BowVector, L1Score) {
  // ||a-b||_1 = 0.5 + 0.25 + 0.75 = 1.5 -> 1 - 0.75 = 0.25 (= min(0.5, 0.25)).
  EXPECT_NEAR(scoreBowVectors(ScoringType::kL1, A(), B()), 0.25, 1e-12);
  EXPECT_NEAR(scoreBowVectors(ScoringType::kL1, A(), A()), 1.0, 1e-12);
}

TEST(BowVector, L2Score) {
  // a = (0.6, 0.8, 0), b = (0, 0.6, 0.8): <a,b> = 0.48 -> 1 - sqrt(0.52).
  BowVector a{{1, 0.6}, {2, 0.8}}, b{{2, 0.6}, {3, 0.8}};
  EXPECT_NEAR(scoreBowVectors(ScoringType::kL2, a, b), 1.0 - std::sqrt(0.52), 1e-12);
  EXPECT_NEAR(scoreBowVectors(ScoringType::kL2, a, a), 1.0, 1e-12);
}

TEST(BowVector, ChiSquareScore) {
  // 2 * (0.5*0.25 / 0.75) = 1/3.
  EXPECT_NEAR(scoreBowVectors(ScoringType::kChiSquare, A(), B()), 1.0 / 3.0, 1e-12);
}

TEST(BowVector, BhattacharyyaScore) {
  // sqrt(0.5 * 0.25) = 0.353553...
  EXPECT_NEAR(scoreBowVectors(ScoringType::kBhattacharyya, A(), B()), std::sqrt(0.125), 1e-12);
}

TEST(BowVector, DotProductScore) {
  EXPECT_NEAR(scoreBowVectors(ScoringType::kDotProduct, A(), B()), 0.125, 1e-12);
}

TEST(BowVector, KlScoreIsExpOfMinusDivergence) {
  // KL(a||b) = 0.5*log(0.5/0.25) + 0.5*(log(0.5) - log(eps)).
  const double log_eps = std::log(2.220446049250313e-16);
  const double kl = 0.5 * std::log(2.0) + 0.5 * (std::log(0.5) - log_eps);
  EXPECT_NEAR(scoreBowVectors(ScoringType::kKl, A(), B()), std::exp(-kl), 1e-15);
  EXPECT_NEAR(scoreBowVectors(ScoringType::kKl, A(), A()), 1.0, 1e-12);
}

TEST(BowVector, DisjointVectorsScoreZero) {
  BowVector a{{1, 1.0}}, b{{2, 1.0}};
  for (auto s : {ScoringType::kL1, ScoringType::kL2, ScoringType::kChiSquare,
                 ScoringType::kBhattacharyya, ScoringType::kDotProduct}) {
    EXPECT_EQ(scoreBowVectors(s, a, b), 0.0) << toString(s);
  }
}

TEST(BowVector, NamesRoundTripAndBadNamesThrow) {
  for (int i = 0; i <= 5; ++i) {
    const auto s = static_cast<ScoringType>(i);
    EXPECT_EQ(scoringTypeFromString(toString(s)), s);
  }
  for (int i = 0; i <= 3; ++i) {
    const auto w = static_cast<WeightingType>(i);
    EXPECT_EQ(weightingTypeFromString(toString(w)), w);
  }
  EXPECT_THROW(scoringTypeFromString("L1"), std::invalid_argument);
  EXPECT_THROW(weightingTypeFromString(""), std::invalid_argument);
}

}  // namespace
}  // namespace bowg
