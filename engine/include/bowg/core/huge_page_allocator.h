// An allocator for the large read-mostly arrays (the vocabulary's nodes: 71 MB
// for k=10 L=6). A fresh array that size costs ~17,000 page faults on first
// touch, more than reading the file itself; in 2 MB pages it costs ~36. Blocks
// of at least kHugePageBytes are 2 MB-aligned and advised as huge pages
// (madvise(MADV_HUGEPAGE): honoured where transparent huge pages are "always"
// or "madvise", ignored elsewhere); smaller ones come from operator new.
#pragma once

#include <cstddef>
#include <new>

namespace bowg {

/// Blocks from this size on are 2 MB-aligned and advised as huge pages.
constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

/// Allocates `bytes` (throws std::bad_alloc); see above.
void* allocateLarge(std::size_t bytes);
/// Frees a block of allocateLarge() of the same `bytes`.
void deallocateLarge(void* p, std::size_t bytes) noexcept;

template <typename T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}  // NOLINT: rebind

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_alloc();
    return static_cast<T*>(allocateLarge(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { deallocateLarge(p, n * sizeof(T)); }
};

template <typename T, typename U>
bool operator==(const HugePageAllocator<T>&, const HugePageAllocator<U>&) {
  return true;
}
template <typename T, typename U>
bool operator!=(const HugePageAllocator<T>&, const HugePageAllocator<U>&) {
  return false;
}

}  // namespace bowg
