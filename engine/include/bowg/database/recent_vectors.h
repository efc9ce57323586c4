// The BoW vectors and raw groups of the database's newest few entries, in a
// ring by id. Every query scores I_{t-1}, one of them (Database::score, the
// normalisers of eqs. 2 and 4), and rebuilding its vectors from the words was
// a third of that (sorting, the weighting, a posting search per word). A
// fixed few kB, not per keyframe.
#pragma once

#include <cstddef>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/bow_vector.h"

namespace bowg {

class RecentVectors {
 public:
  static constexpr std::size_t kEntries = 8;
  struct Entry {
    EntryId id;
    BowVector bow;
    GroupVector raw_groups;
  };
  /// Keeps entry `id`'s vectors, replacing the entry kEntries older;
  /// returns the kept BoW vector.
  const BowVector& remember(EntryId id, BowVector bow, const GroupVector& raw_groups);
  /// The kept copy of entry `id`'s vectors (of a database of `size`
  /// entries), or nullptr.
  const Entry* find(EntryId id, std::size_t size) const;
  void clear() { ring_.clear(); }
  std::size_t heapBytes() const;

 private:
  std::vector<Entry> ring_;
};

}  // namespace bowg
