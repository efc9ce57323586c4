// heapBlockBytes: glibc's chunk sizes, worked out by hand.
#include "bowg/core/heap_bytes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace bowg {
namespace {

TEST(HeapBytes, SmallRequestsTakeAlignedChunksWithASizeWord) {
  EXPECT_EQ(heapBlockBytes(0), 0u);
  EXPECT_EQ(heapBlockBytes(1), 32u);   // the minimum chunk
  EXPECT_EQ(heapBlockBytes(24), 32u);  // 24 + 8 = 32
  EXPECT_EQ(heapBlockBytes(25), 48u);  // 33 -> 48
  EXPECT_EQ(heapBlockBytes(40), 48u);  // 48
  EXPECT_EQ(heapBlockBytes(41), 64u);  // 49 -> 64
  EXPECT_EQ(heapBlockBytes(1000), 1008u);
}

TEST(HeapBytes, LargeRequestsAreMappedInWholePages) {
  EXPECT_EQ(heapBlockBytes(131071), 131088u);            // below the threshold: a chunk
  EXPECT_EQ(heapBlockBytes(131072), 33u * 4096u);        // 131088 bytes -> 33 pages
  EXPECT_EQ(heapBlockBytes(4096u * 100 - 16), 409600u);  // exactly 100 pages
}

TEST(HeapBytes, AVectorCountsItsCapacity) {
  std::vector<std::uint32_t> v;
  EXPECT_EQ(vectorHeapBytes(v), 0u);
  v.reserve(10);  // 40 bytes -> 48
  v.push_back(1);
  EXPECT_EQ(vectorHeapBytes(v), 48u);
}

}  // namespace
}  // namespace bowg
