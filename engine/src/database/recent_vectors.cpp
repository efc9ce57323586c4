#include "bowg/database/recent_vectors.h"

#include <limits>
#include <utility>

#include "bowg/core/heap_bytes.h"

namespace bowg {

#if __cplusplus < 201703L
constexpr std::size_t RecentVectors::kEntries;
#endif

const BowVector& RecentVectors::remember(EntryId id, BowVector bow, const GroupVector& raw_groups) {
  if (ring_.empty()) ring_.resize(kEntries, Entry{std::numeric_limits<EntryId>::max(), {}, {}});
  Entry& r = ring_[id % kEntries];
  r.id = id;
  r.bow = std::move(bow);
  r.raw_groups = raw_groups;
  return r.bow;
}

const RecentVectors::Entry* RecentVectors::find(EntryId id, std::size_t size) const {
  if (ring_.empty()) return nullptr;
  const Entry& r = ring_[id % kEntries];
  return id < size && r.id == id ? &r : nullptr;
}

std::size_t RecentVectors::heapBytes() const {
  std::size_t bytes = vectorHeapBytes(ring_);
  for (const Entry& r : ring_) bytes += vectorHeapBytes(r.bow) + vectorHeapBytes(r.raw_groups);
  return bytes;
}

}  // namespace bowg
