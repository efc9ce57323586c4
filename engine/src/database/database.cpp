#include "bowg/database/database.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "bowg/core/heap_bytes.h"
#include "bowg/scoring/distribution.h"
#include "bowg/vocabulary/vocabulary.h"

namespace bowg {
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
  std::sort(out.begin(), out.end());
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
  word_index_.resize(vocabulary_->wordCount());
  group_index_.resize(vocabulary_->wordCount());
}

void Database::clear() {
  entries_.clear();
  odometers_.clear();
  distributions_.clear();
  group_table_.clear();
  for (auto& l : word_index_) l.clear();
  for (auto& l : group_index_) l.clear();
  word_acc_.clear();
  group_acc_.clear();
  touched_flag_.clear();
  touched_.clear();
}

void Database::setScoring(ScoringType scoring) {
  if (scoring == scoring_) return;
  scoring_ = scoring;
  for (auto& l : word_index_) l.clear();
  for (const auto& e : entries_) indexWords(e.id, bow(e.id));
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
    const std::vector<double> v = distributionVector(e.keypoints, e.centre_x, e.centre_y, m);
    distributions_.insert(distributions_.end(), v.begin(), v.end());
  }
}

void Database::indexWords(EntryId id, const BowVector& bow) {
  for (const auto& w : bow) word_index_[w.first].emplace_back(id, w.second);
}

BowVector Database::bow(EntryId id) const {
  BowVector v = vocabulary_->bowFromWords(entries_.at(id).words);
  normaliseBowVector(scoring_, &v);
  return v;
}

void Database::indexGroups(EntryId id, const GroupVector& group_tf) {
  for (const auto& g : group_tf) group_index_[g.first].emplace_back(id, g.second);
}

EntryId Database::add(DatabaseEntry e) {
  const std::size_t n = e.keypoints.size();
  if (e.descriptors.size() != n || e.words.size() != n) {
    throw std::invalid_argument("Database::add: keypoints (" + std::to_string(n) +
                                "), descriptors (" + std::to_string(e.descriptors.size()) +
                                ") and words (" + std::to_string(e.words.size()) +
                                ") differ in number");
  }
  const std::size_t W = vocabulary_->wordCount();
  for (WordId w : e.words) {
    if (w >= W) throw std::invalid_argument("Database::add: word id out of range");
  }
  for (const auto& g : e.raw_groups) {
    if (g.first >= W) throw std::invalid_argument("Database::add: group id out of range");
  }
  if (!(e.stamp >= 0.0 && e.stamp < kStampLimit)) {
    throw std::invalid_argument("Database::add: stamp " + std::to_string(e.stamp) +
                                " s outside [0, 2^32) s");
  }
  if (!entries_.empty() && !(e.stamp > entries_.back().stamp)) {
    throw std::invalid_argument("Database::add: stamp does not increase");
  }
  if (!std::isnan(e.odometer) && !(std::isfinite(e.odometer) && e.odometer >= 0.0)) {
    throw std::invalid_argument("Database::add: odometer must be NaN (unknown) or finite >= 0");
  }
  e.id = static_cast<EntryId>(entries_.size());
  // Only the TF part of eq. 1 is stored (in the group inverse index): the IDF
  // part changes with every keyframe and is applied at query time.
  const GroupVector group_tf = groupTermFrequencies(e.raw_groups);
  const std::vector<double> dist =
      distributionVector(e.keypoints, e.centre_x, e.centre_y, fan_bins_);
  distributions_.insert(distributions_.end(), dist.begin(), dist.end());
  odometers_.push_back(!std::isnan(e.odometer) ? e.odometer
                       : odometers_.empty()     ? -std::numeric_limits<double>::infinity()
                                                : odometers_.back());
  entries_.push_back(std::move(e));
  const DatabaseEntry& stored = entries_.back();
  indexWords(stored.id, bow(stored.id));
  indexGroups(stored.id, group_tf);
  return stored.id;
}

DatabaseQuery Database::makeQuery(BowVector bow, const GroupVector& raw_groups,
                                  const std::vector<Keypoint>& keypoints, double centre_x,
                                  double centre_y, bool with_distribution) const {
  DatabaseQuery q;
  q.bow = std::move(bow);
  normaliseBowVector(scoring_, &q.bow);
  q.refined_groups = refineGroupWeights(raw_groups, group_table_);
  if (with_distribution)
    q.distribution = distributionVector(keypoints, centre_x, centre_y, fan_bins_);
  return q;
}

std::vector<EntryScores> Database::query(const DatabaseQuery& q, EntryId limit,
                                         bool with_groups) const {
  const std::size_t n = std::min<std::size_t>(limit, entries_.size());
  if (word_acc_.size() < entries_.size()) {
    word_acc_.resize(entries_.size(), 0.0);
    group_acc_.resize(entries_.size(), 0.0);
    touched_flag_.resize(entries_.size(), 0);
  }
  touched_.clear();
  auto touch = [this](EntryId id) {
    if (!touched_flag_[id]) {
      touched_flag_[id] = 1;
      touched_.push_back(id);
    }
  };

  // Word score, accumulated over the shared words only, term by term as
  // scoreBowVectors() does (DBoW2's inverse-index scoring).
  const double base = bowScoreBase(scoring_, q.bow);
  // The metric is chosen once per query, not once per posting.
  auto accumulate = [&](auto term) {
    for (const auto& w : q.bow) {
      for (const auto& p : word_index_[w.first]) {
        if (p.first >= n) break;  // lists are in ascending entry order
        word_acc_[p.first] += term(w.second, p.second);
        touch(p.first);
      }
    }
  };
  switch (scoring_) {
    case ScoringType::kL1:
      accumulate([](double x, double y) { return bowScoreTerm(ScoringType::kL1, x, y); });
      break;
    case ScoringType::kL2:
    case ScoringType::kDotProduct:
      accumulate([](double x, double y) { return x * y; });
      break;
    default:
      accumulate([this](double x, double y) { return bowScoreTerm(scoring_, x, y); });
      break;
  }

  // Group dot product (eq. 3's <w~_q, w~_e>): the entry's refined weight is
  // its stored TF times the table's CURRENT IDF (eq. 1 applied now).
  if (with_groups) {
    for (const auto& g : q.refined_groups) {
      const double idf = group_table_.idf(g.first);
      const double qw = g.second * idf;
      if (qw == 0.0) continue;
      for (const auto& p : group_index_[g.first]) {
        if (p.first >= n) break;
        group_acc_[p.first] += qw * p.second;
        touch(p.first);
      }
    }
  }

  std::sort(touched_.begin(), touched_.end());
  std::vector<EntryScores> out;
  out.reserve(touched_.size());
  for (EntryId id : touched_) {
    EntryScores s;
    s.entry = id;
    // An entry reached through groups only shares no word: its word score is
    // what scoreBowVectors() gives for disjoint vectors (0, or exp(-base) for KL).
    s.s_w = bowScoreFinish(scoring_, word_acc_[id], base);
    s.s_g = with_groups ? groupScoreFromDot(group_acc_[id]) : 0.0;
    if (!q.distribution.empty()) s.s_d = distributionScore(q.distribution, cachedDistribution(id));
    out.push_back(s);
    word_acc_[id] = 0.0;
    group_acc_[id] = 0.0;
    touched_flag_[id] = 0;
  }
  touched_.clear();
  return out;
}

EntryScores Database::score(const DatabaseQuery& q, EntryId id) const {
  const DatabaseEntry& e = entries_.at(id);
  EntryScores s;
  s.entry = id;
  s.s_w = scoreBowVectors(scoring_, q.bow, bow(id));
  s.s_g = groupScore(q.refined_groups, refineGroupWeights(e.raw_groups, group_table_));
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
  std::size_t bytes = vectorHeapBytes(entries_);
  for (const auto& e : entries_) {
    bytes += vectorHeapBytes(e.keypoints) + vectorHeapBytes(e.descriptors) +
             vectorHeapBytes(e.words) + vectorHeapBytes(e.raw_groups);
  }
  bytes += vectorHeapBytes(distributions_) + vectorHeapBytes(odometers_);
  for (const auto& l : word_index_) bytes += vectorHeapBytes(l);
  for (const auto& l : group_index_) bytes += vectorHeapBytes(l);
  bytes += vectorHeapBytes(word_index_) + vectorHeapBytes(group_index_);
  // The group table's hash map: one node (next pointer, key, value) per
  // group and one pointer per bucket (about as many buckets as groups).
  bytes += group_table_.size() *
           (heapBlockBytes(sizeof(void*) + sizeof(WordId) + sizeof(double)) + sizeof(void*));
  return bytes;
}

}  // namespace bowg
