// Bag-of-words vectors, the direct index of one image, and the DBoW2 family
// of weighting and scoring schemes (Galvez-Lopez & Tardos, "Bags of Binary
// Words for Fast Place Recognition in Image Sequences", T-RO 2012).
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

/// Word weighting. Numbering follows DBoW2 so that foreign vocabularies map 1:1.
enum class WeightingType { kTfIdf = 0, kTf = 1, kIdf = 2, kBinary = 3 };

/// Word-score metric. Numbering follows DBoW2. Every metric is returned as a
/// *similarity* (higher = more alike); see scoreBowVectors() for the exact
/// formulas and the one departure from DBoW2 (KL).
enum class ScoringType {
  kL1 = 0,
  kL2 = 1,
  kChiSquare = 2,
  kKl = 3,
  kBhattacharyya = 4,
  kDotProduct = 5
};

/// A sparse weighted word histogram, sorted by word id, no duplicate ids,
/// no zero weights.
using BowEntry = std::pair<WordId, double>;
using BowVector = std::vector<BowEntry>;

/// The direct index of one image: one (node, feature) pair per feature, the
/// node being the vocabulary node at the chosen level that the feature
/// descends through; sorted by node, then feature, so that the features of
/// a node are one run. Flat, without a list per node: a few kilobytes less
/// per keyframe and cheap enough to rebuild from the features' words that
/// the database keeps no direct index (directIndexFromWords).
using DirectIndex = std::vector<std::pair<NodeId, std::uint32_t>>;

/// Scales `v` to unit norm as the scoring type expects (L2 for kL2, none for
/// kDotProduct, L1 otherwise), as DBoW2 does. An empty or all-zero vector is
/// left unchanged.
void normaliseBowVector(ScoringType scoring, BowVector* v);

/// Similarity of two vectors already normalised with normaliseBowVector():
///  - kL1:  1 - 0.5 * ||a - b||_1                       (in [0, 1])
///  - kL2:  1 - sqrt(1 - <a, b>)                         (in [0, 1])
///  - kChiSquare: 2 * sum_i a_i b_i / (a_i + b_i)        (in [0, 1])
///  - kKl:  exp(-KL(a || b)) where absent b_i count as DBoW2's epsilon;
///          DBoW2 returns the divergence itself (lower = better); we map it
///          to a similarity so that every metric can be normalised alike.
///  - kBhattacharyya: sum_i sqrt(a_i b_i)                (in [0, 1])
///  - kDotProduct: sum_i a_i b_i
double scoreBowVectors(ScoringType scoring, const BowVector& a, const BowVector& b);

/// scoreBowVectors() decomposes over the words the two vectors share, which
/// is what lets the database accumulate it through the inverse index
/// (DBoW2's trick): score = bowScoreFinish(acc, base) with acc the sum of
/// bowScoreTerm() over shared words and base = bowScoreBase(query) (non-zero
/// for KL only).
double bowScoreTerm(ScoringType scoring, double query_weight, double entry_weight);
/// bowScoreTerm() of kL1 (DBoW2's default), inline: the database's query
/// calls it for every word posting it walks.
inline double l1ScoreTerm(double x, double y) {
  return std::fabs(x) + std::fabs(y) - std::fabs(x - y);
}
double bowScoreBase(ScoringType scoring, const BowVector& query);
double bowScoreFinish(ScoringType scoring, double acc, double base);

/// Parse / print names ("tf_idf", "tf", "idf", "binary"; "l1", "l2",
/// "chi_square", "kl", "bhattacharyya", "dot_product"). Parsing throws
/// std::invalid_argument naming the bad value.
WeightingType weightingTypeFromString(const std::string& s);
ScoringType scoringTypeFromString(const std::string& s);
std::string toString(WeightingType t);
std::string toString(ScoringType t);

}  // namespace bowg
