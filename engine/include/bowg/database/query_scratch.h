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
  /// One entry's word and group sums side by side: a posting adds to both,
  /// and in a large map each entry's line is a cache miss of its own.
  struct Sums {
    double word = 0.0, group = 0.0;
  };
  /// Dense sums and flags over the entries (instead of a hash map per
  /// query). Between queries every sum and flag is 0 again: a query resets
  /// what it touched.
  std::vector<Sums> sums;
  std::vector<std::uint8_t> touched_flag;
  /// The flagged entries, listed after the walk; one slot past the end: the
  /// branch-free listing.
  std::vector<EntryId> touched;
  /// The query's words and groups with their weights, in id order.
  struct QueryWord {
    WordId w;
    double qw, qg;
  };
  std::vector<QueryWord> words;
};

}  // namespace bowg
