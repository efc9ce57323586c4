// sortIdIndexPairs against std::sort: the radix path (64 pairs and more,
// indexes ascending) and the std::sort path give the same order.
#include "bowg/core/id_index_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace bowg {
namespace {

// Pairs (id, position) as the transform makes them, ids drawn below `limit`.
std::vector<IdIndexPair> positioned(std::size_t n, std::uint32_t limit, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> id(0, limit - 1);
  std::vector<IdIndexPair> out(n);
  for (std::uint32_t i = 0; i < n; ++i) out[i] = {id(rng), i};
  return out;
}

void expectSortedLikeStdSort(std::vector<IdIndexPair> pairs) {
  std::vector<IdIndexPair> expected = pairs;
  std::sort(expected.begin(), expected.end());
  sortIdIndexPairs(&pairs);
  EXPECT_EQ(pairs, expected);
}

TEST(IdIndexSort, SmallInputByHand) {
  // Ids 5, 3, 5, 3 at positions 0-3: the 3s first, each id's positions ascending.
  std::vector<IdIndexPair> p{{5, 0}, {3, 1}, {5, 2}, {3, 3}};
  sortIdIndexPairs(&p);
  EXPECT_EQ(p, (std::vector<IdIndexPair>{{3, 1}, {3, 3}, {5, 0}, {5, 2}}));
}

TEST(IdIndexSort, RadixPathByHand) {
  // 100 pairs: id 7 at the odd positions, 1099 - position at the even ones
  // (1099, 1097, ..., 1001: two bytes). The fifty 7s come first with their
  // positions ascending, then 1001 (position 98), 1003 (96), ..., 1099 (0).
  std::vector<IdIndexPair> p(100);
  for (std::uint32_t i = 0; i < 100; ++i) p[i] = {i % 2 == 0 ? 1099 - i : 7, i};
  sortIdIndexPairs(&p);
  for (std::uint32_t k = 0; k < 50; ++k) {
    EXPECT_EQ(p[k], IdIndexPair(7, 2 * k + 1));
    EXPECT_EQ(p[50 + k], IdIndexPair(1001 + 2 * k, 98 - 2 * k));
  }
}

TEST(IdIndexSort, MatchesStdSortOnWordSizedIds) {
  // A k=10 L=6 vocabulary's words (< 10^6: three bytes) and the counts of
  // an image's features.
  for (std::size_t n : {0u, 1u, 63u, 64u, 500u, 2000u}) {
    expectSortedLikeStdSort(positioned(n, 1000000, static_cast<unsigned>(n)));
  }
}

TEST(IdIndexSort, MatchesStdSortWithRepeatsAndEveryByte) {
  expectSortedLikeStdSort(positioned(700, 5, 1));            // few ids, many repeats
  expectSortedLikeStdSort(positioned(700, 0xffffffffu, 2));  // all four bytes
  std::vector<IdIndexPair> zeros = positioned(300, 1, 3);    // every id 0: no pass
  expectSortedLikeStdSort(zeros);
}

TEST(IdIndexSort, IndexesNotAscendingStillSortByIdThenIndex) {
  std::vector<IdIndexPair> p = positioned(500, 1000, 4);
  std::reverse(p.begin(), p.end());  // indexes descend
  expectSortedLikeStdSort(p);
  std::vector<IdIndexPair> repeated = positioned(500, 1000, 5);
  repeated[10].second = repeated[9].second;  // an index repeats
  expectSortedLikeStdSort(repeated);
}

TEST(IdIndexSort, NullIsAnError) { EXPECT_THROW(sortIdIndexPairs(nullptr), std::invalid_argument); }

}  // namespace
}  // namespace bowg
