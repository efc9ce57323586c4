// Word groups (paper Sec. III-A "Word Group Definition", eq. 1) and the online
// word-group table (Sec. III-A "Word Group Table").
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/scoring/scoring_options.h"

namespace bowg {

/// Sparse word-group weights of one image: (group id = word id i, weight),
/// sorted by id, no duplicates, no zero weights.
using GroupEntry = std::pair<WordId, double>;
using GroupVector = std::vector<GroupEntry>;

/// Raw group weights w_{g,t}^(i) of one image. For feature f with word i and
/// size s_f, the group is i plus every *other* feature of the image whose
/// keypoint lies at distance < radius_scale * s_f; its weight is the number
/// of words in the group minus 1 (= the number of such neighbours). Several
/// features with the same word add their weights into the one group i.
/// Groups of weight 0 (isolated words) are dropped. Neighbours are found
/// with a uniform grid, not all pairs. `words` is index-aligned with
/// `keypoints` (throws std::invalid_argument if the sizes differ).
GroupVector buildWordGroups(const std::vector<Keypoint>& keypoints,
                            const std::vector<WordId>& words,
                            const WordGroupOptions& options);

/// The online word-group table: group id -> sum over database images of
/// w_{g,t}^(i), and the grand total sum_t sum_i w_{g,t}^(i).
class WordGroupTable {
 public:
  WordGroupTable();
  void add(const GroupVector& raw);
  void clear();
  double cumulative(WordId group) const;  ///< 0 when never seen
  double total() const { return total_; }
  std::size_t size() const { return seen_; }  ///< groups seen at least once
  /// Heap bytes held (Database::memoryBytes()).
  std::size_t heapBytes() const;
  /// IDF part of eq. 1: log(total / cumulative(group)); 0 when the group
  /// was never seen (it cannot be shared with any database image then).
  double idf(WordId group) const;
  /// Changes with every add() and clear(), to a value no table had before;
  /// a copy keeps it with the contents. Equal versions: equal IDFs, so that
  /// IDFs read once can be reused while the version stands.
  std::uint64_t version() const { return version_; }

 private:
  // Dense by group id (grown to the largest id seen): a query reads the IDF
  // of each of its ~400 groups, and a hash map node per group cost ~40 bytes
  // per new group, i.e. per keyframe while the vocabulary is far from seen.
  std::vector<double> cumulative_;
  std::size_t seen_ = 0;
  double total_ = 0.0;
  std::uint64_t version_;
};

/// TF part of eq. 1: w / sum_i w over the image (sums to 1).
GroupVector groupTermFrequencies(const GroupVector& raw);

/// Eq. 1, refined weights w~ = TF * IDF with the table's current totals.
/// The BoWG pipeline adds the query's raw weights to the table first, so the
/// IDF is finite for every group of the query.
GroupVector refineGroupWeights(const GroupVector& raw, const WordGroupTable& table);
/// The same, with the IDF of each kept group in `idf` (index-aligned with
/// the result; not touched when null).
GroupVector refineGroupWeights(const GroupVector& raw, const WordGroupTable& table,
                               std::vector<double>* idf);

/// Eq. 3 on the inner product of refined weights: 1 if dot > 1, else
/// 1 - sqrt(1 - dot).
double groupScoreFromDot(double dot);
/// Eq. 3 for two refined vectors.
double groupScore(const GroupVector& a_refined, const GroupVector& b_refined);
/// groupScore(a_refined, refineGroupWeights(b_raw, table)), where `a_idf`
/// holds the table's IDF of each group of a_refined (index-aligned): only
/// the shared groups enter eq. 3's dot product, and a has their IDFs. The
/// same operations in the same order, so the same score, without a
/// logarithm or a vector for b.
double groupScoreWithIdf(const GroupVector& a_refined, const std::vector<double>& a_idf,
                         const GroupVector& b_raw);

}  // namespace bowg
