// heapBlockBytes: glibc's chunk sizes, worked out by hand.
#include "bowg/core/heap_bytes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
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

TEST(HeapBytes, ADequeCountsItsNodesAndItsMap) {
  // 200-byte elements: 512 / 200 = 2 per node, a node of 400 bytes -> 416.
  struct Element {
    char bytes[200];
  };
  std::deque<Element> d;
  // Empty: one node and the initial map of 8 pointers (64 bytes -> 80).
  EXPECT_EQ(dequeHeapBytes(d), 416u + 80u);
  // 5 elements: 5 / 2 + 1 = 3 nodes, the map still 8 pointers.
  for (int i = 0; i < 5; ++i) d.push_back(Element());
  EXPECT_EQ(dequeHeapBytes(d), 3u * 416u + 80u);
  // 40 elements: 21 nodes, a map of at least 23 pointers (184 -> 192).
  for (int i = 0; i < 35; ++i) d.push_back(Element());
  EXPECT_EQ(dequeHeapBytes(d), 21u * 416u + 192u);
  // Elements of 512 bytes or more: one per node.
  struct Big {
    char bytes[600];
  };
  std::deque<Big> b(3);
  EXPECT_EQ(dequeHeapBytes(b), 4u * 608u + 80u);
}

}  // namespace
}  // namespace bowg
