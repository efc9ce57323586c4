#include "bowg/core/id_index_sort.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace bowg {
namespace {

// Below this many pairs the counting passes' fixed cost (256 counters each)
// outweighs std::sort.
const std::size_t kRadixMinimum = 64;

bool indexesAscend(const std::vector<IdIndexPair>& pairs) {
  for (std::size_t i = 1; i < pairs.size(); ++i) {
    if (pairs[i].second <= pairs[i - 1].second) return false;
  }
  return true;
}

}  // namespace

void sortIdIndexPairs(std::vector<IdIndexPair>* pairs) {
  if (pairs == nullptr) throw std::invalid_argument("sortIdIndexPairs: pairs must not be null");
  std::vector<IdIndexPair>& p = *pairs;
  if (p.size() < kRadixMinimum || !indexesAscend(p)) {
    std::sort(p.begin(), p.end());
    return;
  }
  std::uint32_t all_ids = 0;
  for (const IdIndexPair& e : p) all_ids |= e.first;
  // Least significant byte first; each pass is stable, so after the last
  // one equal ids keep their ascending indexes.
  std::vector<IdIndexPair> buffer(p.size());
  std::vector<IdIndexPair>* from = &p;
  std::vector<IdIndexPair>* to = &buffer;
  for (int shift = 0; shift < 32 && (all_ids >> shift) != 0; shift += 8) {
    std::array<std::uint32_t, 257> start{};
    for (const IdIndexPair& e : *from) ++start[((e.first >> shift) & 0xffu) + 1];
    for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
    for (const IdIndexPair& e : *from) (*to)[start[(e.first >> shift) & 0xffu]++] = e;
    std::swap(from, to);
  }
  if (from != &p) p.swap(*from);
}

}  // namespace bowg
