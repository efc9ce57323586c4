// Sorting an image's (word or node id, feature index) pairs: the step that
// turns per-feature words into a BoW vector or a direct index.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace bowg {

using IdIndexPair = std::pair<std::uint32_t, std::uint32_t>;

/// Sorts `pairs` by id, then index: the order of std::sort on the pairs.
/// The pairs are usually made with index = position, so the indexes already
/// ascend and a stable sort by id alone gives that order: then a radix sort
/// over the ids' significant bytes runs (a few passes of O(n) without a
/// comparison branch, where std::sort's comparisons are mispredicted half of
/// the time), else std::sort. O(n) extra memory.
void sortIdIndexPairs(std::vector<IdIndexPair>* pairs);

}  // namespace bowg
