#include "bowg/database/database.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "bowg/core/heap_bytes.h"
#include "bowg/scoring/distribution.h"
#include "bowg/vocabulary/id_index_sort.h"
#include "bowg/vocabulary/vocabulary.h"
#include "core/prefetch.h"

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

// Walks the union of the ids of two id-sorted sparse vectors (a BoW vector
// and a group vector): f(id, a_item, b_item), the item nullptr where that
// vector lacks the id. The inverse index has one posting per id of the union.
template <typename A, typename B, typename F>
void forEachId(const std::vector<A>& a, const std::vector<B>& b, F f) {
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    const bool in_a = i < a.size() && (j == b.size() || a[i].first <= b[j].first);
    const bool in_b = j < b.size() && (i == a.size() || b[j].first <= a[i].first);
    const WordId id = in_a ? a[i].first : b[j].first;
    f(id, in_a ? &a[i] : nullptr, in_b ? &b[j] : nullptr);
    if (in_a) ++i;
    if (in_b) ++j;
  }
}

// The capacity a full posting list of `size` postings grows to: by an
// eighth, not the doubling push_back does. Lists only grow, by one posting
// per keyframe at most, and a doubled list is a quarter empty on average
// (docs/benchmarks.md, "8-byte postings"). The capacity is odd, so that with
// malloc's 8-byte header a list fills its 16-byte chunk. Copies stay
// amortised O(1): ~9 per posting over its life, 8 bytes each.
std::size_t nextPostingCapacity(std::size_t size) {
  static_assert(sizeof(Posting) == 8, "the odd capacities assume 8-byte postings");
  const std::size_t grown = std::max<std::size_t>(3, size + size / 8 + 1);
  return grown | 1u;
}

}  // namespace

DirectIndex directIndexFromWords(const Vocabulary& vocabulary, const std::vector<WordId>& words,
                                 int level) {
  const auto& nodes = vocabulary.nodes();
  DirectIndex out;
  out.reserve(words.size());
  for (std::uint32_t f = 0; f < words.size(); ++f) {
    NodeId n = vocabulary.nodeOfWord(words[f]);
    while (static_cast<int>(nodes[n].level) > level && n != 0) n = nodes[n].parent;
    out.emplace_back(n, f);
  }
  sortIdIndexPairs(&out);
  return out;
}

Database::Database(std::shared_ptr<const Vocabulary> vocabulary, ScoringType scoring,
                   int direct_index_level, int fan_bins)
    : vocabulary_(std::move(vocabulary)),
      scoring_(scoring),
      direct_level_(direct_index_level),
      fan_bins_(fan_bins) {
  if (!vocabulary_ || vocabulary_->empty()) {
    throw std::invalid_argument("Database: vocabulary is null or empty");
  }
  if (fan_bins_ < 1) throw std::invalid_argument("Database: fan_bins must be >= 1");
  index_.resize(vocabulary_->wordCount());
}

void Database::clear() {
  entries_.clear();
  odometers_.clear();
  distributions_.clear();
  group_sums_.clear();
  group_table_.clear();
  for (auto& l : index_) l.clear();
  group_overflow_.clear();
  overflow_begin_.clear();
  archived_groups_.clear();
  recent_.clear();
  searchable_count_ = 0;
  word_acc_.clear();
  group_acc_.clear();
  touched_flag_.clear();
  touched_.clear();
}

void Database::setScoring(ScoringType scoring) {
  if (scoring == scoring_) return;
  scoring_ = scoring;
  recent_.clear();  // their BoW vectors are normalised for the old scoring
  // The same words keep a weight under every scoring (the IDF decides which);
  // only the normalisation changes. Every posting is reset, then each
  // entry's vector is written back.
  for (auto& l : index_) {
    for (Posting& p : l) p.word = 0.f;
  }
  for (const auto& e : entries_) {
    if (!e.searchable) continue;  // no postings: its BoW is rebuilt from its words
    for (const auto& w : bow(e.id)) {
      // add() made a posting for every word of the entry's vector; one is
      // inserted in order should a scoring weigh another word.
      std::vector<Posting>& l = index_[w.first];
      auto it = lowerBoundOfEntry(l.begin(), l.end(), e.id);
      if (it == l.end() || it->entry() != e.id) it = l.insert(it, Posting{e.id, 0.f});
      it->word = static_cast<float>(w.second);
    }
  }
}

void Database::setDirectLevel(int level) {
  // Nothing to rebuild: direct indexes are made from the words on demand.
  direct_level_ = level;
}

void Database::setFanBins(int m) {
  if (m < 1) throw std::invalid_argument("Database::setFanBins: m must be >= 1");
  if (m == fan_bins_) return;
  fan_bins_ = m;
  distributions_.clear();
  distributions_.reserve(entries_.size() * static_cast<std::size_t>(m));
  for (const auto& e : entries_) {
    const std::vector<double> v = distributionVector(e.points.unpack(), e.centre_x, e.centre_y, m);
    distributions_.insert(distributions_.end(), v.begin(), v.end());
  }
}

BowVector Database::bow(EntryId id) const {
  if (const RecentEntry* r = recent(id)) return r->bow;
  return bowOfWords(entries_.at(id).words.unpack());
}

const BowVector& Database::remember(EntryId id, BowVector bow, const GroupVector& raw_groups) {
  if (recent_.empty())
    recent_.resize(kRecentEntries, RecentEntry{std::numeric_limits<EntryId>::max(), {}, {}});
  RecentEntry& r = recent_[id % kRecentEntries];
  r.id = id;
  r.bow = std::move(bow);
  r.raw_groups = raw_groups;
  return r.bow;
}

const Database::RecentEntry* Database::recent(EntryId id) const {
  if (recent_.empty()) return nullptr;
  const RecentEntry& r = recent_[id % kRecentEntries];
  return id < entries_.size() && r.id == id ? &r : nullptr;
}

BowVector Database::bowOfWords(const std::vector<WordId>& words) const {
  BowVector v = vocabulary_->bowFromWords(words);
  normaliseBowVector(scoring_, &v);
  return v;
}

const Posting* Database::posting(WordId w, EntryId id) const {
  const std::vector<Posting>& l = index_[w];
  const auto it = lowerBoundOfEntry(l.begin(), l.end(), id);
  return it != l.end() && it->entry() == id ? &*it : nullptr;
}

double Database::overflowCount(WordId w, EntryId id) const {
  const auto first = group_overflow_.begin() + overflow_begin_[id];
  const auto last = id + 1 < overflow_begin_.size()
                        ? group_overflow_.begin() + overflow_begin_[id + 1]
                        : group_overflow_.end();
  const auto it = std::lower_bound(first, last, w,
                                   [](const GroupCount& o, WordId word) { return o.word < word; });
  // add() wrote one record for every posting it marked as overflowing.
  return static_cast<double>(it->count);
}

GroupVector Database::rawGroups(EntryId id) const {
  if (const RecentEntry* r = recent(id)) return r->raw_groups;
  if (!entries_.at(id).searchable) {
    GroupVector out;
    out.reserve(archived_groups_[id].size());
    for (const GroupCount& g : archived_groups_[id]) out.emplace_back(g.word, g.count);
    return out;
  }
  std::vector<WordId> words = entries_.at(id).words.unpack();
  std::sort(words.begin(), words.end());
  words.erase(std::unique(words.begin(), words.end()), words.end());
  GroupVector out;
  for (WordId w : words) {
    const Posting* p = posting(w, id);
    if (p && p->groupCode() != 0) out.emplace_back(w, groupCount(w, *p));
  }
  return out;
}

EntryId Database::add(DatabaseEntry e, const GroupVector& raw_groups,
                      const std::vector<double>& distribution) {
  return addEntry(std::move(e), raw_groups, distribution, nullptr);
}

EntryId Database::add(DatabaseEntry e, const GroupVector& raw_groups,
                      const DatabaseQuery& queried) {
  if (queried.scoring != scoring_) {
    throw std::invalid_argument("Database::add: the query's BoW vector is normalised for " +
                                toString(queried.scoring) + ", the database scores " +
                                toString(scoring_));
  }
  return addEntry(std::move(e), raw_groups, queried.distribution, &queried.bow);
}

EntryId Database::addEntry(DatabaseEntry e, const GroupVector& raw_groups,
                           const std::vector<double>& distribution, const BowVector* bow) {
  const std::size_t n = e.points.size();
  if (!distribution.empty() && distribution.size() != static_cast<std::size_t>(fan_bins_)) {
    throw std::invalid_argument("Database::add: distribution vector of " +
                                std::to_string(distribution.size()) + " bins, the database has " +
                                std::to_string(fan_bins_));
  }
  if (e.descriptors.size() != n || e.words.size() != n) {
    throw std::invalid_argument("Database::add: keypoints (" + std::to_string(n) +
                                "), descriptors (" + std::to_string(e.descriptors.size()) +
                                ") and words (" + std::to_string(e.words.size()) +
                                ") differ in number");
  }
  const std::size_t W = vocabulary_->wordCount();
  const std::vector<WordId> words = e.words.unpack();
  for (WordId w : words) {
    if (w >= W) throw std::invalid_argument("Database::add: word id out of range");
  }
  {
    // The entry's words in order (a radix sort), walked along the groups
    // and the BoW vector, both sorted by id.
    std::vector<IdIndexPair> sorted(words.size());
    for (std::size_t i = 0; i < words.size(); ++i)
      sorted[i] = {words[i], static_cast<std::uint32_t>(i)};
    sortIdIndexPairs(&sorted);
    const auto hasWord = [&sorted](std::size_t* j, WordId w) {
      while (*j < sorted.size() && sorted[*j].first < w) ++*j;
      return *j < sorted.size() && sorted[*j].first == w;
    };
    WordId previous = 0;
    std::size_t walked = 0;
    for (std::size_t i = 0; i < raw_groups.size(); ++i) {
      const GroupEntry& g = raw_groups[i];
      if (i > 0 && g.first <= previous) {
        throw std::invalid_argument("Database::add: raw groups not sorted by id without repeats");
      }
      previous = g.first;
      if (!hasWord(&walked, g.first)) {
        throw std::invalid_argument("Database::add: word group " + std::to_string(g.first) +
                                    " is not one of the entry's words");
      }
      // Whole counts of neighbours (buildWordGroups), exact in a float.
      if (!(g.second >= 1.0 && g.second < 16777216.0 && g.second == std::floor(g.second))) {
        throw std::invalid_argument("Database::add: word group " + std::to_string(g.first) +
                                    " has weight " + std::to_string(g.second) +
                                    ", not a whole count in [1, 2^24)");
      }
    }
    if (bow != nullptr) {
      std::size_t j = 0;
      for (const BowEntry& b : *bow) {
        if (!hasWord(&j, b.first)) {
          throw std::invalid_argument("Database::add: the query's BoW vector holds word " +
                                      std::to_string(b.first) + ", not one of the entry's");
        }
      }
    }
  }
  if (!(e.stamp >= 0.0 && e.stamp < kStampLimit)) {
    throw std::invalid_argument("Database::add: stamp " + std::to_string(e.stamp) +
                                " s outside [0, 2^32) s");
  }
  if (entries_.size() >= kMaxEntries) {
    throw std::length_error("Database::add: the database holds its maximum of " +
                            std::to_string(kMaxEntries) + " entries");
  }
  if (!entries_.empty() && !(e.stamp > entries_.back().stamp)) {
    throw std::invalid_argument("Database::add: stamp does not increase");
  }
  if (!std::isnan(e.odometer) && !(std::isfinite(e.odometer) && e.odometer >= 0.0)) {
    throw std::invalid_argument("Database::add: odometer must be NaN (unknown) or finite >= 0");
  }
  e.id = static_cast<EntryId>(entries_.size());
  // The raw group weights are stored (in the inverse index) with their sum:
  // eq. 1's TF is raw / sum, and its IDF part changes with every keyframe,
  // so both are applied at query time.
  double group_sum = 0.0;
  for (const auto& g : raw_groups) group_sum += g.second;
  if (!distribution.empty()) {
    distributions_.insert(distributions_.end(), distribution.begin(), distribution.end());
  } else {
    const std::vector<double> dist =
        distributionVector(e.points.unpack(), e.centre_x, e.centre_y, fan_bins_);
    distributions_.insert(distributions_.end(), dist.begin(), dist.end());
  }
  odometers_.push_back(!std::isnan(e.odometer) ? e.odometer
                       : odometers_.empty()     ? -std::numeric_limits<double>::infinity()
                                                : odometers_.back());
  group_sums_.push_back(group_sum);
  entries_.push_back(std::move(e));
  const EntryId id = entries_.back().id;
  overflow_begin_.push_back(group_overflow_.size());
  archived_groups_.emplace_back();
  if (!entries_.back().searchable) {
    // Out of the inverse index: the BoW vector comes from the words as for
    // every entry; the raw groups are all that has to be kept.
    std::vector<GroupCount>& kept = archived_groups_.back();
    kept.reserve(raw_groups.size());
    for (const auto& g : raw_groups) {
      kept.push_back(GroupCount{g.first, static_cast<std::uint32_t>(g.second)});
    }
    remember(id, bow != nullptr ? *bow : bowOfWords(words), raw_groups);
    return id;
  }
  ++searchable_count_;
  // One posting per word of the BoW vector or group (both sorted by id).
  const BowVector& kept = remember(id, bow != nullptr ? *bow : bowOfWords(words), raw_groups);
  forEachId(kept, raw_groups,
            [&](WordId w, const BowEntry* word, const GroupEntry* group) {
              std::uint32_t code = 0;
              if (group) {
                const auto count = static_cast<std::uint32_t>(group->second);
                code = count < Posting::kGroupOverflow ? count : Posting::kGroupOverflow;
                if (code == Posting::kGroupOverflow)
                  group_overflow_.push_back(GroupCount{w, count});
              }
              std::vector<Posting>& list = index_[w];
              if (list.size() == list.capacity()) list.reserve(nextPostingCapacity(list.size()));
              list.push_back(Posting{id | code << Posting::kEntryBits,
                                     word ? static_cast<float>(word->second) : 0.f});
            });
  return id;
}

DatabaseQuery Database::makeQuery(BowVector bow, const GroupVector& raw_groups,
                                  const std::vector<ImagePoint>& points, double centre_x,
                                  double centre_y, bool with_distribution) const {
  DatabaseQuery q;
  q.bow = std::move(bow);
  normaliseBowVector(scoring_, &q.bow);
  q.scoring = scoring_;
  q.refined_groups = refineGroupWeights(raw_groups, group_table_, &q.group_idf);
  q.group_table_version = group_table_.version();
  if (with_distribution) q.distribution = distributionVector(points, centre_x, centre_y, fan_bins_);
  return q;
}

std::vector<EntryScores> Database::query(const DatabaseQuery& q, EntryId limit,
                                         bool with_groups) const {
  const std::size_t n = std::min<std::size_t>(limit, entries_.size());
  if (word_acc_.size() < entries_.size()) {
    word_acc_.resize(entries_.size(), 0.0);
    group_acc_.resize(entries_.size(), 0.0);
    touched_flag_.resize(entries_.size(), 0);
    touched_.resize(entries_.size() + 1);  // one past the last: the branch-free touch
  }
  // The touched entries are touched_[0, touched).
  std::size_t touched = 0;
  auto touch = [this, &touched](EntryId id) {
    if (!touched_flag_[id]) {
      touched_flag_[id] = 1;
      touched_[touched++] = id;
    }
  };

  // One walk over the query's words and groups (both sorted by id; a group
  // without a word weight is possible, e.g. a word of IDF 0). Word score:
  // accumulated over the shared words only, term by term as
  // scoreBowVectors() does (DBoW2's inverse-index scoring). Group score: the
  // dot product of eq. 3, <w~_q, w~_e>, with the entry's refined weight
  // = raw / sum (its TF, the division applied per entry below) times the
  // table's CURRENT IDF (eq. 1 applied now).
  const double base = bowScoreBase(scoring_, q.bow);
  const GroupVector& groups = q.refined_groups;
  static const GroupVector kNoGroups;
  const bool idf_read = queryIdfCurrent(q);
  query_words_.clear();
  forEachId(q.bow, with_groups ? groups : kNoGroups,
            [&](WordId w, const BowEntry* word, const GroupEntry* group) {
              const double qw = word ? word->second : 0.0;
              const double idf = !group ? 0.0
                                 : idf_read
                                     ? q.group_idf[static_cast<std::size_t>(group - groups.data())]
                                     : group_table_.idf(w);
              const double qg = group ? group->second * idf : 0.0;
              if (qw != 0.0 || qg != 0.0) query_words_.push_back(QueryWord{w, qw, qg});
            });
  // visit(w, qw, qg) for each query word, in order.
  auto forEachQueryWord = [&](auto visit) {
    const std::size_t m = query_words_.size();
    for (std::size_t i = 0; i < m; ++i) {
      // The lists lie scattered over the index: the walk waited on the first
      // load of each. Ask for the list headers 8 words ahead and their first
      // postings 4 ahead.
      if (i + 8 < m) prefetchRead(&index_[query_words_[i + 8].w]);
      if (i + 4 < m) prefetchRead(index_[query_words_[i + 4].w].data());
      visit(query_words_[i].w, query_words_[i].qw, query_words_[i].qg);
    }
  };
  auto accumulate = [&](auto term) {
    forEachQueryWord([&](WordId w, double qw, double qg) {
      for (const Posting& p : index_[w]) {
        const EntryId e = p.entry();
        if (e >= n) break;  // lists are in ascending entry order
        if (qw != 0.0 && p.word != 0.f) {
          word_acc_[e] += term(qw, static_cast<double>(p.word));
          touch(e);
        }
        const std::uint32_t code = p.groupCode();
        if (qg != 0.0 && code != 0) {
          group_acc_[e] += qg * groupCount(w, p);
          touch(e);
        }
      }
    });
  };
  // The same for a metric whose term is +0 when either weight is 0 (L1:
  // |x| + 0 - |x|; L2 and the dot product: x * 0), so that the word term
  // needs no test, nor the group term (qg * 0 for a posting without a
  // group): adding +0 to a sum that starts at +0 changes no bit. The entry
  // is touched as above, without a branch: written past the end, and the
  // end moved when it is new. In an aliased pipe most postings' tests go
  // either way and were mispredicted.
  auto accumulateZeroSafe = [&](auto term) {
    forEachQueryWord([&](WordId w, double qw, double qg) {
      const bool with_word = qw != 0.0, with_group = qg != 0.0;
      for (const Posting& p : index_[w]) {
        const EntryId e = p.entry();
        if (e >= n) break;  // lists are in ascending entry order
        const std::uint32_t code = p.groupCode();
        word_acc_[e] += term(qw, static_cast<double>(p.word));
        // A count in the overflow table is looked up only when it counts.
        const double count = code < Posting::kGroupOverflow ? static_cast<double>(code)
                             : with_group                   ? overflowCount(w, e)
                                                            : 0.0;
        group_acc_[e] += qg * count;
        const std::uint8_t active =
            static_cast<std::uint8_t>((with_word & (p.word != 0.f)) | (with_group & (code != 0)));
        touched_[touched] = e;
        touched += active & (touched_flag_[e] ^ 1u);
        touched_flag_[e] |= active;
      }
    });
  };
  // The metric is chosen once per query, not once per posting.
  switch (scoring_) {
    case ScoringType::kL1:
      accumulateZeroSafe([](double x, double y) { return l1ScoreTerm(x, y); });
      break;
    case ScoringType::kL2:
    case ScoringType::kDotProduct:
      accumulateZeroSafe([](double x, double y) { return x * y; });
      break;
    default:
      accumulate([this](double x, double y) { return bowScoreTerm(scoring_, x, y); });
      break;
  }

  // Ascending entry order: sorted, or, where a query touches a large share
  // of the database (an aliased pipe revisited lap after lap), read off the
  // flags in one pass, which is cheaper than sorting that many ids.
  if (touched * 16 < n) {
    std::sort(touched_.begin(), touched_.begin() + static_cast<std::ptrdiff_t>(touched));
  } else {
    std::size_t k = 0;
    for (EntryId id = 0; id < n; ++id) {
      if (touched_flag_[id]) touched_[k++] = id;
    }
  }
  std::vector<EntryScores> out;
  out.reserve(touched);
  for (std::size_t t = 0; t < touched; ++t) {
    const EntryId id = touched_[t];
    EntryScores s;
    s.entry = id;
    // An entry reached through groups only shares no word: its word score is
    // what scoreBowVectors() gives for disjoint vectors (0, or exp(-base) for KL).
    s.s_w = bowScoreFinish(scoring_, word_acc_[id], base);
    const double sum = group_sums_[id];  // > 0 for an entry reached through a group
    s.s_g = with_groups ? groupScoreFromDot(sum > 0.0 ? group_acc_[id] / sum : 0.0) : 0.0;
    if (!q.distribution.empty()) s.s_d = distributionScore(q.distribution, cachedDistribution(id));
    out.push_back(s);
    word_acc_[id] = 0.0;
    group_acc_[id] = 0.0;
    touched_flag_[id] = 0;
  }
  return out;
}

EntryScores Database::score(const DatabaseQuery& q, EntryId id) const {
  if (id >= entries_.size())
    throw std::out_of_range("Database::score: no entry " + std::to_string(id));
  EntryScores s;
  s.entry = id;
  s.s_w = scoreBowVectors(scoring_, q.bow, bow(id));
  s.s_g = queryIdfCurrent(q)
              ? groupScoreWithIdf(q.refined_groups, q.group_idf, rawGroups(id))
              : groupScore(q.refined_groups, refineGroupWeights(rawGroups(id), group_table_));
  if (!q.distribution.empty()) s.s_d = distributionScore(q.distribution, cachedDistribution(id));
  return s;
}

const std::vector<double>& Database::cachedDistribution(EntryId id) const {
  const std::size_t m = static_cast<std::size_t>(fan_bins_);
  const auto first = distributions_.begin() + static_cast<std::ptrdiff_t>(id * m);
  distribution_scratch_.assign(first, first + static_cast<std::ptrdiff_t>(m));
  return distribution_scratch_;
}

std::vector<double> Database::distribution(EntryId id) const {
  if (id >= entries_.size())
    throw std::out_of_range("Database::distribution: no entry " + std::to_string(id));
  return cachedDistribution(id);
}

std::size_t Database::memoryBytes() const {
  std::size_t bytes = dequeHeapBytes(entries_);
  for (const auto& e : entries_) {
    bytes += e.points.heapBytes() + vectorHeapBytes(e.descriptors) + e.words.heapBytes();
  }
  bytes +=
      vectorHeapBytes(distributions_) + vectorHeapBytes(odometers_) + vectorHeapBytes(group_sums_);
  for (const auto& l : index_) bytes += vectorHeapBytes(l);
  bytes += vectorHeapBytes(group_overflow_) + vectorHeapBytes(overflow_begin_);
  bytes += vectorHeapBytes(archived_groups_);
  for (const auto& g : archived_groups_) bytes += vectorHeapBytes(g);
  bytes += vectorHeapBytes(index_) + group_table_.heapBytes();
  bytes += vectorHeapBytes(recent_);
  for (const RecentEntry& r : recent_) {
    bytes += vectorHeapBytes(r.bow) + vectorHeapBytes(r.raw_groups);
  }
  return bytes;
}

}  // namespace bowg
