// The word-group table (paper Sec. III-A "Word Group Table"), eq. 1's
// refined weights and eq. 3's group score, with values worked out by hand in
// the comments.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

#include "bowg/scoring/word_groups.h"

namespace bowg {
namespace {

// Table after adding image A = {1: 2, 2: 1} and image B = {1: 1, 3: 3}:
// cumulative 1 -> 3, 2 -> 1, 3 -> 3; total = 3 + 4 = 7.
WordGroupTable twoImageTable() {
  WordGroupTable t;
  t.add({{1, 2.0}, {2, 1.0}});
  t.add({{1, 1.0}, {3, 3.0}});
  return t;
}

TEST(WordGroupTable, AccumulatesPerGroupAndInTotal) {
  const WordGroupTable t = twoImageTable();
  EXPECT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t.cumulative(1), 3.0);
  EXPECT_DOUBLE_EQ(t.cumulative(2), 1.0);
  EXPECT_DOUBLE_EQ(t.cumulative(3), 3.0);
  EXPECT_DOUBLE_EQ(t.cumulative(99), 0.0);
  EXPECT_DOUBLE_EQ(t.total(), 7.0);
}

TEST(WordGroupTable, IdfIsLogOfTotalOverCumulative) {
  const WordGroupTable t = twoImageTable();
  EXPECT_NEAR(t.idf(1), std::log(7.0 / 3.0), 1e-12);  // 0.847298
  EXPECT_NEAR(t.idf(2), std::log(7.0), 1e-12);        // 1.945910
  EXPECT_DOUBLE_EQ(t.idf(99), 0.0);                   // never seen
}

TEST(WordGroupTable, ClearForgetsEverything) {
  WordGroupTable t = twoImageTable();
  t.clear();
  EXPECT_EQ(t.size(), 0u);
  EXPECT_DOUBLE_EQ(t.total(), 0.0);
  EXPECT_DOUBLE_EQ(t.cumulative(1), 0.0);
  EXPECT_DOUBLE_EQ(t.idf(1), 0.0);
}

TEST(WordGroupTable, RejectsNonPositiveWeights) {
  WordGroupTable t;
  EXPECT_THROW(t.add({{1, 0.0}}), std::invalid_argument);
  EXPECT_THROW(t.add({{1, -2.0}}), std::invalid_argument);
  EXPECT_THROW(t.add({{1, std::numeric_limits<double>::quiet_NaN()}}), std::invalid_argument);
  EXPECT_EQ(t.size(), 0u);  // nothing half-added
}

TEST(WordGroupTable, VersionChangesWithTheContentsAndTravelsWithACopy) {
  WordGroupTable t;
  const WordGroupTable empty_copy = t;
  EXPECT_NE(WordGroupTable().version(), t.version());  // no two tables share one
  const std::uint64_t before = t.version();
  t.add({{1, 2.0}});
  const std::uint64_t after_add = t.version();
  EXPECT_NE(after_add, before);
  const WordGroupTable copy = t;
  EXPECT_EQ(copy.version(), after_add);
  t.clear();
  EXPECT_NE(t.version(), after_add);
  EXPECT_NE(t.version(), before);  // cleared is not the empty table it was
  EXPECT_EQ(empty_copy.version(), before);
  EXPECT_THROW(t.add({{1, 0.0}}), std::invalid_argument);
}

TEST(Eq1, TermFrequenciesSumToOne) {
  // {1: 2, 3: 3}: sum 5 -> 0.4, 0.6.
  const GroupVector tf = groupTermFrequencies({{1, 2.0}, {3, 3.0}});
  ASSERT_EQ(tf.size(), 2u);
  EXPECT_EQ(tf[0].first, 1u);
  EXPECT_DOUBLE_EQ(tf[0].second, 0.4);
  EXPECT_EQ(tf[1].first, 3u);
  EXPECT_DOUBLE_EQ(tf[1].second, 0.6);
  EXPECT_TRUE(groupTermFrequencies({}).empty());
}

TEST(Eq1, RefinedWeightIsTfTimesIdf) {
  // Query {1: 2, 3: 3} against the two-image table:
  //   w~1 = 2/5 * log(7/3) = 0.4 * 0.8472979 = 0.3389191
  //   w~3 = 3/5 * log(7/3) = 0.6 * 0.8472979 = 0.5083787
  const GroupVector r = refineGroupWeights({{1, 2.0}, {3, 3.0}}, twoImageTable());
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].first, 1u);
  EXPECT_NEAR(r[0].second, 0.3389191, 1e-6);
  EXPECT_EQ(r[1].first, 3u);
  EXPECT_NEAR(r[1].second, 0.5083787, 1e-6);
}

TEST(Eq1, RefinedWeightsReportTheIdfOfEachKeptGroup) {
  // {1: 2, 2: 1, 9: 4} against the two-image table: idf 1 = log(7/3),
  // idf 2 = log 7; group 9 unknown (idf 0) is dropped with its IDF.
  std::vector<double> idf{42.0};  // replaced, not appended to
  const GroupVector r = refineGroupWeights({{1, 2.0}, {2, 1.0}, {9, 4.0}}, twoImageTable(), &idf);
  ASSERT_EQ(r.size(), 2u);
  ASSERT_EQ(idf.size(), 2u);
  EXPECT_NEAR(idf[0], 0.8472979, 1e-6);
  EXPECT_NEAR(idf[1], 1.9459101, 1e-6);
  // w~ = tf * idf: 2/7 * 0.8472979 = 0.2420851, 1/7 * 1.9459101 = 0.2779872.
  EXPECT_NEAR(r[0].second, 0.2420851, 1e-6);
  EXPECT_NEAR(r[1].second, 0.2779872, 1e-6);
  EXPECT_EQ(r, refineGroupWeights({{1, 2.0}, {2, 1.0}, {9, 4.0}}, twoImageTable()));
}

TEST(Eq1, GroupsWithZeroIdfAreDropped) {
  // Table {5: 2} only: idf(5) = log(2/2) = 0; group 6 unknown: idf 0. The
  // refined vector must hold no zero weights.
  WordGroupTable t;
  t.add({{5, 2.0}});
  EXPECT_TRUE(refineGroupWeights({{5, 2.0}, {6, 1.0}}, t).empty());
}

TEST(Eq3, ScoreFromDot) {
  EXPECT_DOUBLE_EQ(groupScoreFromDot(0.0), 0.0);   // 1 - sqrt(1)
  EXPECT_DOUBLE_EQ(groupScoreFromDot(0.75), 0.5);  // 1 - sqrt(0.25)
  EXPECT_DOUBLE_EQ(groupScoreFromDot(1.0), 1.0);   // 1 - sqrt(0)
  EXPECT_DOUBLE_EQ(groupScoreFromDot(1.5), 1.0);   // dot > 1: clamp branch
  EXPECT_DOUBLE_EQ(groupScoreFromDot(40.0), 1.0);
  EXPECT_THROW(groupScoreFromDot(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST(Eq3, ScoreOfTwoVectors) {
  // Shared group 2 only: dot = 0.5 * 0.5 = 0.25 -> 1 - sqrt(0.75) = 0.1339746.
  const GroupVector a{{1, 0.5}, {2, 0.5}}, b{{2, 0.5}, {3, 1.0}};
  EXPECT_NEAR(groupScore(a, b), 1.0 - std::sqrt(0.75), 1e-12);
  EXPECT_NEAR(groupScore(b, a), 1.0 - std::sqrt(0.75), 1e-12);
  // dot = 2.0 * 0.6 = 1.2 > 1 -> 1.
  EXPECT_DOUBLE_EQ(groupScore({{1, 2.0}}, {{1, 0.6}}), 1.0);
  // Nothing shared.
  EXPECT_DOUBLE_EQ(groupScore({{1, 0.5}}, {{2, 0.5}}), 0.0);
  EXPECT_DOUBLE_EQ(groupScore({}, {}), 0.0);
}

TEST(Eq3, EndToEndOnTwoImages) {
  // Image A raw {1: 2, 2: 1}, image B raw {1: 1, 3: 3}; table holds both
  // (total 7; cumulative 1: 3, 2: 1, 3: 3).
  //   A: w~1 = 2/3 log(7/3) = 0.5648653, w~2 = 1/3 log 7 = 0.6486367
  //   B: w~1 = 1/4 log(7/3) = 0.2118245, w~3 = 3/4 log(7/3) = 0.6354734
  //   dot = 0.5648653 * 0.2118245 = 0.1196523
  //   s_g = 1 - sqrt(1 - 0.1196523) = 0.0617315
  const WordGroupTable t = twoImageTable();
  const GroupVector a = refineGroupWeights({{1, 2.0}, {2, 1.0}}, t);
  const GroupVector b = refineGroupWeights({{1, 1.0}, {3, 3.0}}, t);
  EXPECT_NEAR(groupScore(a, b), 0.0617315, 1e-6);
}

TEST(Eq3, ScoreWithTheQuerysIdfByHand) {
  // As EndToEndOnTwoImages, B given raw: only group 1 is shared, B's tf 1/4
  // times A's idf of it, log(7/3): s_g = 0.0617315 again.
  const WordGroupTable t = twoImageTable();
  std::vector<double> a_idf;
  const GroupVector a = refineGroupWeights({{1, 2.0}, {2, 1.0}}, t, &a_idf);
  EXPECT_NEAR(groupScoreWithIdf(a, a_idf, {{1, 1.0}, {3, 3.0}}), 0.0617315, 1e-6);
  EXPECT_DOUBLE_EQ(groupScoreWithIdf(a, a_idf, {{3, 3.0}}), 0.0);  // nothing shared
  EXPECT_DOUBLE_EQ(groupScoreWithIdf(a, a_idf, {}), 0.0);
}

TEST(Eq3, ScoreWithTheQuerysIdfIsTheRefinedScoreExactly) {
  // Random tables and images: bit for bit the score of the two refined
  // vectors, also where the second image has groups of IDF 0 or unknown
  // to the table (they change its TF denominator, not the dot product).
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> id(0, 60), count(1, 9), size(0, 40);
  const auto image = [&] {
    std::map<WordId, double> m;
    const int n = size(rng);
    for (int i = 0; i < n; ++i) m[static_cast<WordId>(id(rng))] += count(rng);
    return GroupVector(m.begin(), m.end());
  };
  for (int trial = 0; trial < 300; ++trial) {
    WordGroupTable t;
    for (int i = 0; i < 1 + trial % 7; ++i) {
      const GroupVector g = image();
      if (!g.empty()) t.add(g);
    }
    if (trial % 5 == 0) t.add({{61, 3.0}});  // a group only the table has
    std::vector<double> a_idf;
    const GroupVector a = refineGroupWeights(image(), t, &a_idf);
    GroupVector b = image();
    if (trial % 3 == 0) b.emplace_back(70, 2.0);  // unknown to the table
    EXPECT_EQ(groupScoreWithIdf(a, a_idf, b), groupScore(a, refineGroupWeights(b, t)))
        << "trial " << trial;
  }
}

TEST(Eq3, ScoreWithTheQuerysIdfRejectsBadInput) {
  const WordGroupTable t = twoImageTable();
  std::vector<double> a_idf;
  const GroupVector a = refineGroupWeights({{1, 2.0}, {2, 1.0}}, t, &a_idf);
  EXPECT_THROW(groupScoreWithIdf(a, {0.5}, {{1, 1.0}}), std::invalid_argument);
  EXPECT_THROW(groupScoreWithIdf(a, a_idf, {{1, 0.0}}), std::invalid_argument);
  EXPECT_THROW(groupScoreWithIdf(a, a_idf, {{1, -1.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace bowg
