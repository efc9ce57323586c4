#include "bowg/database/inverse_index.h"

#include <algorithm>

#include "bowg/core/heap_bytes.h"
#include "database/id_union.h"

namespace bowg {

#if __cplusplus < 201703L
// Before C++17 a static constexpr member a reference binds to (std::min,
// gtest's EXPECT_EQ) needs one definition outside the class.
constexpr std::uint32_t Posting::kEntryBits;
constexpr std::uint32_t Posting::kEntryMask;
constexpr std::uint32_t Posting::kGroupOverflow;
#endif

namespace {

// The first posting of `list` whose entry is not below `id` (lists are in
// ascending entry order).
template <typename It>
It lowerBoundOfEntry(It first, It last, EntryId id) {
  return std::lower_bound(first, last, id,
                          [](const Posting& p, EntryId e) { return p.entry() < e; });
}

// The capacity a full posting list of `size` postings grows to: by an
// eighth, not the doubling push_back does. Lists only grow, by one posting
// per keyframe at most, and a doubled list is a quarter empty on average
// (docs/benchmarks.md, "8-byte postings, lists grown by an eighth"). The capacity is odd, so that
// with malloc's 8-byte header a list fills its 16-byte chunk. Copies stay
// amortised O(1): ~9 per posting over its life, 8 bytes each.
std::size_t nextPostingCapacity(std::size_t size) {
  static_assert(sizeof(Posting) == 8, "the odd capacities assume 8-byte postings");
  const std::size_t grown = std::max<std::size_t>(3, size + size / 8 + 1);
  return grown | 1u;
}

}  // namespace

void InverseIndex::reset(std::size_t words) {
  clear();
  lists_.resize(words);
}

void InverseIndex::clear() {
  for (auto& l : lists_) l.clear();
  overflow_.clear();
  overflow_begin_.clear();
  archived_.clear();
  group_sums_.clear();
  searchable_count_ = 0;
}

void InverseIndex::addEntryRecords(const GroupVector& raw_groups) {
  // The raw group weights are stored with their sum: eq. 1's TF is raw /
  // sum, and its IDF part changes with every keyframe, so both are applied
  // at query time.
  double group_sum = 0.0;
  for (const auto& g : raw_groups) group_sum += g.second;
  group_sums_.push_back(group_sum);
  overflow_begin_.push_back(overflow_.size());
  archived_.emplace_back();
}

void InverseIndex::addArchived(const GroupVector& raw_groups) {
  addEntryRecords(raw_groups);
  std::vector<GroupCount>& kept = archived_.back();
  kept.reserve(raw_groups.size());
  for (const auto& g : raw_groups) {
    kept.push_back(GroupCount{g.first, static_cast<std::uint32_t>(g.second)});
  }
}

void InverseIndex::addSearchable(EntryId id, const BowVector& bow, const GroupVector& raw_groups) {
  addEntryRecords(raw_groups);
  ++searchable_count_;
  forEachId(bow, raw_groups, [&](WordId w, const BowEntry* word, const GroupEntry* group) {
    std::uint32_t code = 0;
    if (group) {
      const auto count = static_cast<std::uint32_t>(group->second);
      code = count < Posting::kGroupOverflow ? count : Posting::kGroupOverflow;
      if (code == Posting::kGroupOverflow) overflow_.push_back(GroupCount{w, count});
    }
    std::vector<Posting>& list = lists_[w];
    if (list.size() == list.capacity()) list.reserve(nextPostingCapacity(list.size()));
    list.push_back(
        Posting{id | code << Posting::kEntryBits, word ? static_cast<float>(word->second) : 0.f});
  });
}

const Posting* InverseIndex::posting(WordId w, EntryId id) const {
  const std::vector<Posting>& l = lists_[w];
  const auto it = lowerBoundOfEntry(l.begin(), l.end(), id);
  return it != l.end() && it->entry() == id ? &*it : nullptr;
}

double InverseIndex::overflowCount(WordId w, EntryId id) const {
  const auto first = overflow_.begin() + overflow_begin_[id];
  const auto last = id + 1 < overflow_begin_.size() ? overflow_.begin() + overflow_begin_[id + 1]
                                                    : overflow_.end();
  const auto it = std::lower_bound(first, last, w,
                                   [](const GroupCount& o, WordId word) { return o.word < word; });
  // addSearchable() wrote one record for every posting it marked as
  // overflowing.
  return static_cast<double>(it->count);
}

GroupVector InverseIndex::rawGroups(EntryId id, bool searchable, const PackedWords& packed) const {
  GroupVector out;
  if (!searchable) {
    out.reserve(archived_[id].size());
    for (const GroupCount& g : archived_[id]) out.emplace_back(g.word, g.count);
    return out;
  }
  std::vector<WordId> words = packed.unpack();
  std::sort(words.begin(), words.end());
  words.erase(std::unique(words.begin(), words.end()), words.end());
  for (WordId w : words) {
    const Posting* p = posting(w, id);
    if (p && p->groupCode() != 0) out.emplace_back(w, groupCount(w, *p));
  }
  return out;
}

void InverseIndex::clearWordWeights() {
  for (auto& l : lists_) {
    for (Posting& p : l) p.word = 0.f;
  }
}

void InverseIndex::setWordWeight(WordId w, EntryId id, float weight) {
  std::vector<Posting>& l = lists_[w];
  auto it = lowerBoundOfEntry(l.begin(), l.end(), id);
  if (it == l.end() || it->entry() != id) it = l.insert(it, Posting{id, 0.f});
  it->word = weight;
}

std::size_t InverseIndex::heapBytes() const {
  std::size_t bytes = vectorHeapBytes(group_sums_) + vectorHeapBytes(lists_);
  for (const auto& l : lists_) bytes += vectorHeapBytes(l);
  bytes += vectorHeapBytes(overflow_) + vectorHeapBytes(overflow_begin_);
  bytes += vectorHeapBytes(archived_);
  for (const auto& g : archived_) bytes += vectorHeapBytes(g);
  return bytes;
}

}  // namespace bowg
