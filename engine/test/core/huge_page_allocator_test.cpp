// HugePageAllocator: large blocks 2 MB-aligned, small ones from operator new,
// both usable as a vector's storage.
#include "bowg/core/huge_page_allocator.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace bowg {
namespace {

TEST(HugePageAllocator, LargeBlocksAreAlignedToHugePages) {
  const std::size_t bytes = kHugePageBytes * 3 + 100;
  void* p = allocateLarge(bytes);
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % kHugePageBytes, 0u);
  // The whole block is writable.
  static_cast<unsigned char*>(p)[0] = 1;
  static_cast<unsigned char*>(p)[bytes - 1] = 2;
  deallocateLarge(p, bytes);
}

TEST(HugePageAllocator, VectorsOfAnySizeKeepTheirValues) {
  for (std::size_t n : {std::size_t{0}, std::size_t{10}, kHugePageBytes / 8 + 3}) {
    std::vector<std::uint64_t, HugePageAllocator<std::uint64_t>> v(n, 7);
    for (std::size_t i = 0; i < n; ++i) v[i] = i;
    v.push_back(n);  // a reallocation moves the values across block sizes
    for (std::size_t i = 0; i <= n; ++i) ASSERT_EQ(v[i], i);
  }
}

TEST(HugePageAllocator, ImpossibleSizesThrowBadAlloc) {
  HugePageAllocator<std::uint64_t> a;
  EXPECT_THROW(a.allocate(static_cast<std::size_t>(-1) / 4), std::bad_alloc);
}

}  // namespace
}  // namespace bowg
