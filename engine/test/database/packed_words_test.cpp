#include "bowg/database/packed_words.h"

#include <gtest/gtest.h>

#include <vector>

#include "bowg/core/heap_bytes.h"

namespace bowg {
namespace {

TEST(PackedWords, TheLargestIdSetsTheBytesPerWord) {
  EXPECT_EQ(PackedWords().bytesPerWord(), 0);
  EXPECT_EQ(PackedWords({0, 0}).bytesPerWord(), 1);
  EXPECT_EQ(PackedWords({3, 255}).bytesPerWord(), 1);
  EXPECT_EQ(PackedWords({3, 256}).bytesPerWord(), 2);
  EXPECT_EQ(PackedWords({65535}).bytesPerWord(), 2);
  EXPECT_EQ(PackedWords({65536}).bytesPerWord(), 3);  // a k=10 L=6 vocabulary's ids
  EXPECT_EQ(PackedWords({16777215}).bytesPerWord(), 3);
  EXPECT_EQ(PackedWords({16777216}).bytesPerWord(), 4);
  EXPECT_EQ(PackedWords({0xffffffffu}).bytesPerWord(), 4);
}

TEST(PackedWords, IdsComeBackExactly) {
  for (const std::vector<WordId>& given :
       {std::vector<WordId>{}, std::vector<WordId>{7}, std::vector<WordId>{9999, 0, 9999, 1, 256},
        std::vector<WordId>{999999, 65536, 0, 16777215, 0x00ff00ffu},
        std::vector<WordId>{0xffffffffu, 0x80000000u, 1, 0x01020304u}}) {
    const PackedWords p(given);
    ASSERT_EQ(p.size(), given.size());
    EXPECT_EQ(p.empty(), given.empty());
    EXPECT_EQ(p.unpack(), given);
    for (std::size_t i = 0; i < given.size(); ++i) EXPECT_EQ(p[i], given[i]) << i;
  }
}

TEST(PackedWords, HeapBytesAreTheIdsBytes) {
  // 500 ids below 2^24: 1,500 bytes, a 1,508-byte request rounded up to a
  // 1,520-byte malloc chunk; as 4-byte ids 2,000 -> 2,016.
  std::vector<WordId> given;
  for (WordId i = 0; i < 500; ++i) given.push_back(i * 2000);  // up to 998,000
  const PackedWords p(given);
  EXPECT_EQ(p.bytesPerWord(), 3);
  EXPECT_EQ(p.heapBytes(), 1520u);
  EXPECT_EQ(vectorHeapBytes(std::vector<WordId>(given)), 2016u);
  EXPECT_EQ(PackedWords().heapBytes(), 0u);
}

}  // namespace
}  // namespace bowg
