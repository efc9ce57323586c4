// The working memory of Database::query, owned by whoever runs the queries
// (the loop detector keeps one across keyframes): a query then allocates
// nothing once the buffers have grown to the database. Not shared between
// threads, like the detector.
#pragma once

#include <cstdint>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

struct QueryScratch {
  /// Dense accumulators over the entries and the entries touched (instead
  /// of a hash map per query). Between queries every accumulator and flag
  /// is 0 again: a query resets what it touched.
  /// An entry's word and group sums side by side: a posting adds to both,
  /// and in a large map each entry's line was a cache miss of its own.
  struct Sums {
    double word = 0.0, group = 0.0;
  };
  std::vector<Sums> sums;
  std::vector<std::uint8_t> touched_flag;
  std::vector<EntryId> touched;  ///< one slot past the end: the branch-free touch
  /// The query's words and groups with their weights, in id order.
  struct QueryWord {
    WordId w;
    double qw, qg;
  };
  std::vector<QueryWord> words;
};

}  // namespace bowg
