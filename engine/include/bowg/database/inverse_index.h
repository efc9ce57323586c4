// The database's one inverse index for words and word groups (paper Sec.
// III-A "BoWG Database"): word -> postings (entry, normalised BoW weight, raw
// group weight) in 8 bytes, as DBoW2's word index with the group's weight
// beside it (a group's id is its word's id, and an image's groups are among
// its words). Group counts too large for a posting live in an overflow table;
// an entry kept out of the index (DatabaseEntry::searchable false) keeps its
// raw groups apart; every entry's group sum is kept for eq. 1's TF.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/database/packed_words.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/bow_vector.h"

namespace bowg {

/// One posting of the inverse index, 8 bytes: entry() holds the word (BoW
/// weight `word`, 0 when the word weighs nothing in the entry's vector, e.g.
/// IDF 0) and/or its group (raw weight: a whole count of neighbours, 0 when
/// the entry has no such group). The entry id takes the low 24 bits of `key`
/// and the group count the high 8; a count of kGroupOverflow or more is kept
/// in the index's overflow table (rare: a group counts the features within
/// a keypoint's radius). A BoW weight keeps 24 bits (a float); scores are
/// accumulated in double.
struct Posting {
  static constexpr std::uint32_t kEntryBits = 24;
  static constexpr std::uint32_t kEntryMask = (1u << kEntryBits) - 1;
  /// Group code meaning "look the count up in the overflow table".
  static constexpr std::uint32_t kGroupOverflow = 255;

  std::uint32_t key;
  float word;

  EntryId entry() const { return key & kEntryMask; }
  std::uint32_t groupCode() const { return key >> kEntryBits; }
};

class InverseIndex {
 public:
  /// Empties the index and gives it one list per word of a vocabulary.
  void reset(std::size_t words);
  void clear();

  /// Entry `id` (the next id) into the index: one posting per id of `bow`
  /// or `raw_groups` (both sorted by id; counts whole and >= 1, checked by
  /// the caller).
  void addSearchable(EntryId id, const BowVector& bow, const GroupVector& raw_groups);
  /// Entry `id` (the next id) kept out of the index: no postings, its raw
  /// groups kept apart for rawGroups().
  void addArchived(const GroupVector& raw_groups);

  /// Word `w`'s postings, entries ascending.
  const std::vector<Posting>& list(WordId w) const { return lists_[w]; }
  /// Entry `id`'s posting in word `w`'s list, or nullptr.
  const Posting* posting(WordId w, EntryId id) const;
  /// The raw group weight posting `p` of word `w`'s list holds (0: none):
  /// its code, or the overflow table's count. Inline: the query reads it for
  /// every group posting it walks.
  double groupCount(WordId w, const Posting& p) const {
    const std::uint32_t code = p.groupCode();
    return code < Posting::kGroupOverflow ? static_cast<double>(code) : overflowCount(w, p.entry());
  }
  /// The count addSearchable() put in the overflow table for entry `id`'s
  /// group `w`.
  double overflowCount(WordId w, EntryId id) const;
  /// The sum of entry `id`'s raw group weights (eq. 1's TF divides by it).
  double groupSum(EntryId id) const { return group_sums_[id]; }
  /// Entry `id`'s raw groups as they were added: read back through its
  /// words' postings, or the groups kept apart when it is not searchable.
  GroupVector rawGroups(EntryId id, bool searchable, const PackedWords& words) const;
  std::size_t searchableCount() const { return searchable_count_; }

  /// For a change of scoring: every posting's BoW weight to 0, then each
  /// entry's weights written back (a posting inserted in order where the
  /// new scoring weighs a word the old one did not).
  void clearWordWeights();
  void setWordWeight(WordId w, EntryId id, float weight);

  /// Heap bytes with glibc's per-allocation overhead.
  std::size_t heapBytes() const;

 private:
  struct GroupCount {
    WordId word;
    std::uint32_t count;
  };
  /// word (= group id) -> postings, entries ascending.
  std::vector<std::vector<Posting>> lists_;
  /// Group counts too large for a posting's 8 bits, in (entry, word) order:
  /// entries are added in id order with their words ascending. Entry e's
  /// records are [overflow_begin_[e], overflow_begin_[e + 1]) (the table's
  /// end for the last entry): a query looks a count up among its entry's few
  /// records, not by a binary search of the whole table (pipe images with
  /// large multi-scale features overflow often: that search was a third of
  /// the query's time on a 6,000-keyframe circuit).
  std::vector<GroupCount> overflow_;
  std::vector<std::size_t> overflow_begin_;
  /// Per entry the raw groups of an entry that is not searchable, by word;
  /// empty for a searchable entry. Read by entry only, never walked by a
  /// query. A vector per entry rather than one array: one array of every
  /// such entry's groups (~2.4 kB each) would be copied whole when it grows,
  /// tens of MB and a keyframe of 100+ ms at 17,000 keyframes.
  std::vector<std::vector<GroupCount>> archived_;
  /// Per entry the sum of its raw group weights: eq. 1's TF is raw / sum,
  /// applied once per scored entry instead of once per posting.
  std::vector<double> group_sums_;
  std::size_t searchable_count_ = 0;

  void addEntryRecords(const GroupVector& raw_groups);
};

}  // namespace bowg
