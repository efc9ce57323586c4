// Combination of the normalised scores (eqs. 5, 9) and the adaptive temporal
// score (eqs. 6-7), with values worked out by hand.
#include "bowg/scoring/similarity.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "bowg/core/errors.h"

namespace bowg {
namespace {

// eta_w = 0.8, eta_g = 0.6, eta_d = 0.4 with lambda_1 = 0.5, lambda_2 = 0.3.
class CombineSimilarity : public ::testing::Test {
 protected:
  double combine(bool groups_on, bool distribution_on) {
    WordGroupOptions g;
    g.enabled = groups_on;
    DistributionOptions d;
    d.enabled = distribution_on;
    SimilarityOptions s;
    s.lambda_1 = 0.5;
    s.lambda_2 = 0.3;
    return combineSimilarity(0.8, 0.6, 0.4, g, d, s);
  }
};

TEST_F(CombineSimilarity, GroupsAndDistribution) {
  // Eq. 9: 0.5*0.8 + 0.3*0.6 + 0.2*0.4 = 0.40 + 0.18 + 0.08 = 0.66.
  EXPECT_NEAR(combine(true, true), 0.66, 1e-12);
}

TEST_F(CombineSimilarity, GroupsOnly) {
  // Eq. 5: 0.5*0.8 + 0.5*0.6 = 0.70.
  EXPECT_NEAR(combine(true, false), 0.70, 1e-12);
}

TEST_F(CombineSimilarity, DistributionOnly) {
  // Eq. 5 with eta_d: 0.5*0.8 + 0.5*0.4 = 0.60.
  EXPECT_NEAR(combine(false, true), 0.60, 1e-12);
}

TEST_F(CombineSimilarity, PureBagOfWords) { EXPECT_DOUBLE_EQ(combine(false, false), 0.8); }

TEST(CombineSimilarityInput, UnusedScoresMayBeUnsetButUsedOnesMustBeFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  WordGroupOptions off;
  off.enabled = false;
  const DistributionOptions dist_off;  // off by default
  const SimilarityOptions s;
  EXPECT_DOUBLE_EQ(combineSimilarity(0.3, nan, nan, off, dist_off, s), 0.3);
  EXPECT_THROW(combineSimilarity(nan, 0.1, 0.1, off, dist_off, s), std::invalid_argument);
  EXPECT_THROW(combineSimilarity(0.3, nan, 0.1, WordGroupOptions(), dist_off, s),
               std::invalid_argument);
}

TemporalScoreOptions temporal(double w_max, double alpha) {
  TemporalScoreOptions o;
  o.w_max = w_max;
  o.alpha = alpha;
  return o;
}

TEST(Eq6, PreviousWeightByHand) {
  // w_max 0.6, alpha 0.2, eta 0.5, eta_prev 0.3: ((0.5-0.3)/0.2)^2 = 1 ->
  // w_prev = 0.6 / (1 + 1) = 0.3.
  EXPECT_NEAR(previousScoreWeight(0.5, 0.3, temporal(0.6, 0.2)), 0.3, 1e-12);
  // Symmetric in the sign of the difference.
  EXPECT_NEAR(previousScoreWeight(0.3, 0.5, temporal(0.6, 0.2)), 0.3, 1e-12);
}

TEST(Eq6, EqualScoresGetTheFullWeight) {
  EXPECT_DOUBLE_EQ(previousScoreWeight(0.42, 0.42, temporal(0.6, 0.2)), 0.6);
}

TEST(Eq6, LargeDifferencesGetAlmostNoWeight) {
  // (10 / 0.2)^2 = 2500 -> 0.6 / 2501 = 2.399e-4.
  const double w = previousScoreWeight(10.0, 0.0, temporal(0.6, 0.2));
  EXPECT_NEAR(w, 0.6 / 2501.0, 1e-15);
  EXPECT_LT(w, 1e-3);
  EXPECT_LT(previousScoreWeight(1e200, 0.0, temporal(0.6, 0.2)), 1e-300);
}

TEST(Eq7, TemporalScoreByHand) {
  // w_prev = 0.3 (above): eta_temp = 0.3*0.3 + 0.7*0.5 = 0.09 + 0.35 = 0.44.
  EXPECT_NEAR(temporalScore(0.5, 0.3, temporal(0.6, 0.2)), 0.44, 1e-12);
}

TEST(Eq7, UnscoredPreviousEntryCountsAsZero) {
  // eta_prev = 0: ((0.5 - 0)/0.2)^2 = 6.25 -> w_prev = 0.6/7.25 = 0.0827586;
  // eta_temp = 0.9172414 * 0.5 = 0.4586207.
  EXPECT_NEAR(temporalScore(0.5, 0.0, temporal(0.6, 0.2)), 0.4586207, 1e-7);
}

TEST(Eq7, EqualScoresStayPut) {
  // w_prev = w_max: 0.6*0.7 + 0.4*0.7 = 0.7.
  EXPECT_NEAR(temporalScore(0.7, 0.7, temporal(0.6, 0.2)), 0.7, 1e-12);
}

TEST(Eq7, SwitchedOffReturnsTheCurrentScore) {
  TemporalScoreOptions o = temporal(0.6, 0.2);
  o.enabled = false;
  EXPECT_DOUBLE_EQ(previousScoreWeight(0.5, 0.3, o), 0.0);
  EXPECT_DOUBLE_EQ(temporalScore(0.5, 0.3, o), 0.5);
}

TEST(Eq7, BadInputThrows) {
  EXPECT_THROW(previousScoreWeight(0.5, 0.3, temporal(0.6, 0.0)), InvalidParameter);
  EXPECT_THROW(temporalScore(0.5, 0.3, temporal(1.0, 0.2)), InvalidParameter);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(temporalScore(nan, 0.3, temporal(0.6, 0.2)), std::invalid_argument);
  EXPECT_THROW(temporalScore(0.5, nan, temporal(0.6, 0.2)), std::invalid_argument);
}

TEST(CandidateScoreCombiner, GivesTheCheckedFunctionsValuesByHand) {
  // The hand cases above through the per-query combiner: eq. 9 0.66, then
  // eqs. 6-7 on 0.5 after 0.3: 0.44.
  WordGroupOptions g;
  DistributionOptions d;
  d.enabled = true;
  SimilarityOptions s;
  s.lambda_1 = 0.5;
  s.lambda_2 = 0.3;
  const CandidateScoreCombiner both(g, d, s, temporal(0.6, 0.2));
  EXPECT_NEAR(both.similarity(0.8, 0.6, 0.4), 0.66, 1e-12);
  EXPECT_DOUBLE_EQ(both.similarity(0.8, 0.6, 0.4), combineSimilarity(0.8, 0.6, 0.4, g, d, s));
  EXPECT_NEAR(both.temporal(0.5, 0.3, 7), 0.44, 1e-12);
  EXPECT_DOUBLE_EQ(both.temporal(0.5, 0.3, 7), temporalScore(0.5, 0.3, temporal(0.6, 0.2)));
  // Groups only (eq. 5: 0.70) and without the temporal score (eta_sim back).
  g.enabled = true;
  d.enabled = false;
  TemporalScoreOptions off = temporal(0.6, 0.2);
  off.enabled = false;
  const CandidateScoreCombiner groups_only(g, d, s, off);
  EXPECT_NEAR(groups_only.similarity(0.8, 0.6, 0.4), 0.70, 1e-12);
  EXPECT_DOUBLE_EQ(groups_only.temporal(0.5, 0.3, 7), 0.5);
}

TEST(CandidateScoreCombiner, ChecksTheOptionsOnceAndEveryFinalScore) {
  const WordGroupOptions g;
  const DistributionOptions d;
  SimilarityOptions s;
  EXPECT_THROW(CandidateScoreCombiner(g, d, s, temporal(0.6, 0.0)), InvalidParameter);
  s.lambda_1 = 0.8;
  s.lambda_2 = 0.4;  // eq. 9's weight of eta_d would be negative
  EXPECT_THROW(CandidateScoreCombiner(g, d, SimilarityOptions(s), temporal(0.6, 0.2)),
               InvalidParameter);
  // A score that is not finite, current or previous, is refused naming the
  // entry.
  const CandidateScoreCombiner combine(g, d, SimilarityOptions(), temporal(0.6, 0.2));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& scores : {std::make_pair(nan, 0.3), std::make_pair(0.5, nan),
                             std::make_pair(inf, 0.3), std::make_pair(0.5, inf)}) {
    try {
      combine.temporal(scores.first, scores.second, 42);
      FAIL() << scores.first << " after " << scores.second << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("entry 42"), std::string::npos) << e.what();
    }
  }
  // A score of a switched-off module may stay unset.
  WordGroupOptions groups_off;
  groups_off.enabled = false;
  const CandidateScoreCombiner bow(groups_off, d, SimilarityOptions(), temporal(0.6, 0.2));
  EXPECT_DOUBLE_EQ(bow.similarity(0.3, nan, nan), 0.3);
}

TEST(Normalise, DividesByTheNormaliser) {
  // eta = s(I_t, I_tj) / s(I_t, I_t-1) = 0.12 / 0.4 = 0.3 (eqs. 2, 4).
  EXPECT_NEAR(normaliseScore(0.12, 0.4), 0.3, 1e-12);
}

}  // namespace
}  // namespace bowg
