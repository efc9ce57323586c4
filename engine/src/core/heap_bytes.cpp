#include "bowg/core/heap_bytes.h"

#include <algorithm>

namespace bowg {

std::size_t heapBlockBytes(std::size_t requested) {
  if (requested == 0) return 0;
  // glibc's default mmap threshold (M_MMAP_THRESHOLD) and page size.
  const std::size_t kMmapThreshold = 128 * 1024, kPage = 4096;
  if (requested >= kMmapThreshold) return (requested + 16 + kPage - 1) / kPage * kPage;
  return std::max<std::size_t>(32, (requested + 8 + 15) / 16 * 16);
}

}  // namespace bowg
