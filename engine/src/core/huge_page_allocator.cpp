#include "bowg/core/huge_page_allocator.h"

#include <sys/mman.h>

#include <cstdlib>

namespace bowg {

void* allocateLarge(std::size_t bytes) {
  if (bytes < kHugePageBytes) return ::operator new(bytes);
  // Rounded up to whole huge pages, so that the last one is not shared with
  // other allocations.
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  void* p = nullptr;
  if (::posix_memalign(&p, kHugePageBytes, rounded) != 0) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  // Advice only: without transparent huge pages the block is used as is.
  (void)::madvise(p, rounded, MADV_HUGEPAGE);
#endif
  return p;
}

void deallocateLarge(void* p, std::size_t bytes) noexcept {
  if (bytes < kHugePageBytes) {
    ::operator delete(p);
  } else {
    std::free(p);
  }
}

}  // namespace bowg
