#include "bowg/database/database.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "bowg/core/heap_bytes.h"
#include "bowg/core/id_index_sort.h"
#include "bowg/scoring/distribution.h"
#include "bowg/vocabulary/vocabulary.h"

namespace bowg {
namespace {

// The entry's raw groups must be sorted by id without repeats, each one of
// the entry's words (`sorted`: its words with their feature index, by id),
// with a whole count of neighbours (buildWordGroups), exact in a float; and
// a BoW vector given with the entry must hold only its words.
void checkGroupsAndBow(const std::vector<IdIndexPair>& sorted, const GroupVector& raw_groups,
                       const BowVector* bow) {
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
    if (!(g.second >= 1.0 && g.second < 16777216.0 && g.second == std::floor(g.second))) {
      throw std::invalid_argument("Database::add: word group " + std::to_string(g.first) +
                                  " has weight " + std::to_string(g.second) +
                                  ", not a whole count in [1, 2^24)");
    }
  }
  if (bow == nullptr) return;
  std::size_t j = 0;
  for (const BowEntry& b : *bow) {
    if (!hasWord(&j, b.first)) {
      throw std::invalid_argument("Database::add: the query's BoW vector holds word " +
                                  std::to_string(b.first) + ", not one of the entry's");
    }
  }
}

}  // namespace

const std::vector<Descriptor>& DatabaseEntry::descriptorsRead(
    std::vector<Descriptor>* scratch) const {
  if (!on_disk.file) return descriptors;
  on_disk.file->read(on_disk.offset, on_disk.count, on_disk.checksum, scratch);
  return *scratch;
}

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
      distributions_(fan_bins) {
  if (!vocabulary_ || vocabulary_->empty()) {
    throw std::invalid_argument("Database: vocabulary is null or empty");
  }
  if (fan_bins < 1) throw std::invalid_argument("Database: fan_bins must be >= 1");
  index_.reset(vocabulary_->wordCount());
}

void Database::clear() {
  entries_.clear();
  odometers_.clear();
  distributions_.reset(distributions_.bins());
  group_table_.clear();
  index_.clear();
  recent_.clear();
  missions_.clear();
}

void Database::restoreMissions(const std::vector<Mission>& missions) {
  if (!entries_.empty()) {
    throw std::logic_error("Database::restoreMissions: the database holds entries");
  }
  missions_.restore(missions);
}

void Database::setScoring(ScoringType scoring) {
  if (scoring == scoring_) return;
  scoring_ = scoring;
  recent_.clear();  // their BoW vectors are normalised for the old scoring
  // The same words keep a weight under every scoring (the IDF decides which);
  // only the normalisation changes. Every posting is reset, then each
  // entry's vector is written back.
  index_.clearWordWeights();
  for (const auto& e : entries_) {
    if (!e.searchable) continue;  // no postings: its BoW is rebuilt from its words
    for (const auto& w : bow(e.id))
      index_.setWordWeight(w.first, e.id, static_cast<float>(w.second));
  }
}

void Database::setDirectLevel(int level) {
  // Nothing to rebuild: direct indexes are made from the words on demand.
  direct_level_ = level;
}

void Database::setFanBins(int m) {
  if (m < 1) throw std::invalid_argument("Database::setFanBins: m must be >= 1");
  if (m == distributions_.bins()) return;
  distributions_.reset(m);
  distributions_.reserve(entries_.size());
  for (const auto& e : entries_) {
    distributions_.append(distributionVector(e.points.unpack(), e.centre_x, e.centre_y, m));
  }
}

BowVector Database::bow(EntryId id) const {
  if (const RecentVectors::Entry* r = recent_.find(id, entries_.size())) return r->bow;
  return bowOfWords(entries_.at(id).words.unpack());
}

BowVector Database::bowOfWords(const std::vector<WordId>& words) const {
  BowVector v = vocabulary_->bowFromWords(words);
  normaliseBowVector(scoring_, &v);
  return v;
}

GroupVector Database::rawGroups(EntryId id) const {
  if (const RecentVectors::Entry* r = recent_.find(id, entries_.size())) return r->raw_groups;
  const DatabaseEntry& e = entries_.at(id);
  return index_.rawGroups(id, e.searchable, e.words);
}

CountedGroups Database::addToGroupTable(GroupVector raw) {
  if (!raw.empty()) group_table_.add(raw);
  return CountedGroups(this, std::move(raw));
}

void Database::checkCounted(const CountedGroups& counted, const char* function, bool to_add) const {
  const char* problem = nullptr;
  if (counted.owner_ == nullptr) {
    problem = ": the word groups were moved from";
  } else if (counted.owner_ != this) {
    problem = ": the word groups were counted by another database";
  } else if (to_add && counted.added_) {
    problem = ": the word groups were added already (one entry per counting)";
  }
  if (problem != nullptr) throw std::logic_error(std::string(function) + problem);
}

EntryId Database::add(DatabaseEntry e, CountedGroups&& counted,
                      const std::vector<double>& distribution) {
  return addEntry(std::move(e), &counted, distribution, nullptr);
}

EntryId Database::add(DatabaseEntry e, CountedGroups&& counted, const DatabaseQuery& queried) {
  return addEntry(std::move(e), &counted, queried.distribution, &queried);
}

void Database::checkEntry(const DatabaseEntry& e, const std::vector<WordId>& words,
                          const GroupVector& raw_groups, const std::vector<double>& distribution,
                          const BowVector* bow) const {
  const std::size_t n = e.points.size();
  if (!distribution.empty() && distribution.size() != static_cast<std::size_t>(fanBins())) {
    throw std::invalid_argument("Database::add: distribution vector of " +
                                std::to_string(distribution.size()) + " bins, the database has " +
                                std::to_string(fanBins()));
  }
  if (e.on_disk.file && !e.descriptors.empty()) {
    throw std::invalid_argument("Database::add: descriptors both in memory and on disk");
  }
  if (e.descriptorCount() != n || e.words.size() != n) {
    throw std::invalid_argument("Database::add: keypoints (" + std::to_string(n) +
                                "), descriptors (" + std::to_string(e.descriptorCount()) +
                                ") and words (" + std::to_string(e.words.size()) +
                                ") differ in number");
  }
  const std::size_t W = vocabulary_->wordCount();
  for (WordId w : words) {
    if (w >= W) throw std::invalid_argument("Database::add: word id out of range");
  }
  // The entry's words in order (a radix sort), walked along the groups and
  // the BoW vector, both sorted by id.
  std::vector<IdIndexPair> sorted(words.size());
  for (std::size_t i = 0; i < words.size(); ++i) {
    sorted[i] = {words[i], static_cast<std::uint32_t>(i)};
  }
  sortIdIndexPairs(&sorted);
  checkGroupsAndBow(sorted, raw_groups, bow);
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
  if (missions_.find(e.mission) == nullptr) {
    throw std::invalid_argument("Database::add: mission " + std::to_string(e.mission) +
                                " is not one of the database's missions");
  }
}

EntryId Database::addEntry(DatabaseEntry e, CountedGroups* counted,
                           const std::vector<double>& distribution, const DatabaseQuery* queried) {
  checkCounted(*counted, "Database::add", true);
  if (queried != nullptr && queried->scoring != scoring_) {
    throw std::invalid_argument("Database::add: the query's BoW vector is normalised for " +
                                toString(queried->scoring) + ", the database scores " +
                                toString(scoring_));
  }
  const GroupVector& raw_groups = counted->raw_;
  const BowVector* bow = queried != nullptr ? &queried->bow : nullptr;
  const std::vector<WordId> words = e.words.unpack();
  checkEntry(e, words, raw_groups, distribution, bow);
  const EntryId id = static_cast<EntryId>(entries_.size());
  e.id = id;
  distributions_.append(!distribution.empty() ? distribution
                                              : distributionVector(e.points.unpack(), e.centre_x,
                                                                   e.centre_y, fanBins()));
  odometers_.push_back(!std::isnan(e.odometer) ? e.odometer
                       : odometers_.empty()    ? -std::numeric_limits<double>::infinity()
                                               : odometers_.back());
  const bool searchable = e.searchable;
  missions_.countEntry(e.mission);
  entries_.push_back(std::move(e));
  // The BoW vector comes from the words for every entry; an entry out of
  // the inverse index keeps only its raw groups.
  const BowVector& kept =
      recent_.remember(id, bow != nullptr ? *bow : bowOfWords(words), raw_groups);
  if (searchable) {
    index_.addSearchable(id, kept, raw_groups);
  } else {
    index_.addArchived(raw_groups);
  }
  counted->added_ = true;
  return id;
}

DatabaseQuery Database::makeQuery(BowVector bow, const CountedGroups& counted,
                                  const std::vector<ImagePoint>& points, double centre_x,
                                  double centre_y, bool with_distribution) const {
  checkCounted(counted, "Database::makeQuery", false);
  const GroupVector& raw_groups = counted.raw_;
  DatabaseQuery q;
  q.bow = std::move(bow);
  normaliseBowVector(scoring_, &q.bow);
  q.scoring = scoring_;
  q.refined_groups = refineGroupWeights(raw_groups, group_table_, &q.group_idf);
  q.group_table_version = group_table_.version();
  if (with_distribution) q.distribution = distributionVector(points, centre_x, centre_y, fanBins());
  return q;
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
  if (!q.distribution.empty()) s.s_d = distributionScore(q.distribution, distribution(id));
  return s;
}

std::vector<double> Database::distribution(EntryId id) const {
  if (id >= entries_.size())
    throw std::out_of_range("Database::distribution: no entry " + std::to_string(id));
  std::vector<double> out;
  distributions_.copy(id, &out);
  return out;
}

std::size_t Database::memoryBytes() const {
  std::size_t bytes = dequeHeapBytes(entries_);
  for (const auto& e : entries_) {
    bytes += e.points.heapBytes() + vectorHeapBytes(e.descriptors) + e.words.heapBytes();
  }
  bytes += distributions_.heapBytes() + vectorHeapBytes(odometers_);
  bytes += index_.heapBytes() + group_table_.heapBytes() + recent_.heapBytes();
  return bytes;
}

}  // namespace bowg
