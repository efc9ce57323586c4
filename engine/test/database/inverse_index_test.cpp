// The inverse index alone: postings per id of the union of words and groups,
// group counts beyond a posting's byte in the overflow table, raw groups read
// back, an entry kept out of the index, a scoring change's weights.
#include "bowg/database/inverse_index.h"

#include <gtest/gtest.h>

namespace bowg {
namespace {

TEST(InverseIndex, OnePostingPerWordOrGroupWithBothWeights) {
  InverseIndex index;
  index.reset(10);
  // Word 2 has a weight and a group of 3; word 4 a weight only; word 7 a
  // group only (a word of IDF 0 can still group).
  index.addSearchable(0, BowVector{{2, 0.5}, {4, 0.25}}, GroupVector{{2, 3}, {7, 1}});
  ASSERT_EQ(index.list(2).size(), 1u);
  EXPECT_EQ(index.list(2)[0].entry(), 0u);
  EXPECT_FLOAT_EQ(index.list(2)[0].word, 0.5f);
  EXPECT_EQ(index.groupCount(2, index.list(2)[0]), 3.0);
  EXPECT_EQ(index.list(4)[0].groupCode(), 0u);
  EXPECT_FLOAT_EQ(index.list(7)[0].word, 0.f);
  EXPECT_EQ(index.groupSum(0), 4.0);  // 3 + 1: eq. 1's TF denominator
  EXPECT_TRUE(index.list(3).empty());
  EXPECT_EQ(index.searchableCount(), 1u);
}

TEST(InverseIndex, CountsBeyondAByteLiveInTheOverflowTablePerEntry) {
  InverseIndex index;
  index.reset(10);
  index.addSearchable(0, BowVector{{1, 0.1}}, GroupVector{{1, 300}, {5, 254}});
  index.addSearchable(1, BowVector{{1, 0.2}}, GroupVector{{1, 1000}, {5, 255}});
  EXPECT_EQ(index.list(5)[0].groupCode(), 254u);  // the largest count a posting holds
  EXPECT_EQ(index.list(5)[1].groupCode(), Posting::kGroupOverflow);
  EXPECT_EQ(index.groupCount(1, index.list(1)[0]), 300.0);
  EXPECT_EQ(index.groupCount(1, index.list(1)[1]), 1000.0);
  EXPECT_EQ(index.groupCount(5, index.list(5)[1]), 255.0);
}

TEST(InverseIndex, RawGroupsReadBackForIndexedAndArchivedEntries) {
  InverseIndex index;
  index.reset(10);
  index.addSearchable(0, BowVector{{2, 0.5}, {6, 0.5}}, GroupVector{{6, 400}});
  index.addArchived(GroupVector{{3, 2}, {8, 1}});  // entry 1: no postings
  const PackedWords words0(std::vector<WordId>{6, 2, 6});
  EXPECT_EQ(index.rawGroups(0, true, words0), (GroupVector{{6, 400}}));
  EXPECT_EQ(index.rawGroups(1, false, PackedWords()), (GroupVector{{3, 2}, {8, 1}}));
  EXPECT_TRUE(index.list(3).empty());
  EXPECT_EQ(index.groupSum(1), 3.0);
  EXPECT_EQ(index.searchableCount(), 1u);
}

TEST(InverseIndex, AScoringChangeRewritesAndInsertsWordWeightsInOrder) {
  InverseIndex index;
  index.reset(10);
  index.addSearchable(0, BowVector{{2, 0.5}}, GroupVector{});
  index.addSearchable(2, BowVector{{2, 0.25}}, GroupVector{});
  index.clearWordWeights();
  EXPECT_EQ(index.list(2)[0].word, 0.f);
  index.setWordWeight(2, 1, 0.75f);  // a word the old scoring did not weigh
  index.setWordWeight(2, 2, 0.125f);
  ASSERT_EQ(index.list(2).size(), 3u);
  EXPECT_EQ(index.list(2)[1].entry(), 1u);
  EXPECT_EQ(index.list(2)[1].word, 0.75f);
  EXPECT_EQ(index.posting(2, 2)->word, 0.125f);
  EXPECT_EQ(index.posting(2, 3), nullptr);
}

}  // namespace
}  // namespace bowg
