#include "bowg/vocabulary/bow_vector.h"

#include <cmath>
#include <stdexcept>

namespace bowg {
namespace {

// DBoW2's epsilon for words absent from the database vector in the KL
// divergence (log of DBL_EPSILON).
const double kLogEps = std::log(2.220446049250313e-16);

}  // namespace

void normaliseBowVector(ScoringType scoring, BowVector* v) {
  if (scoring == ScoringType::kDotProduct) return;
  double norm = 0.0;
  if (scoring == ScoringType::kL2) {
    for (const auto& e : *v) norm += e.second * e.second;
    norm = std::sqrt(norm);
  } else {
    for (const auto& e : *v) norm += std::fabs(e.second);
  }
  if (norm <= 0.0) return;
  for (auto& e : *v) e.second /= norm;
}

double bowScoreTerm(ScoringType scoring, double x, double y) {
  switch (scoring) {
    case ScoringType::kL1:
      return l1ScoreTerm(x, y);
    case ScoringType::kL2:
    case ScoringType::kDotProduct:
      return x * y;
    case ScoringType::kChiSquare:
      return x + y != 0.0 ? x * y / (x + y) : 0.0;
    case ScoringType::kKl:
      // Replaces the epsilon term of the base by the real one.
      return (x > 0 && y > 0) ? x * (kLogEps - std::log(y)) : 0.0;
    case ScoringType::kBhattacharyya:
      return std::sqrt(x * y);
  }
  return 0.0;
}

double bowScoreBase(ScoringType scoring, const BowVector& query) {
  // KL covers every word of the query: absent database words count as
  // DBoW2's epsilon; the shared words' terms correct that.
  double base = 0.0;
  if (scoring == ScoringType::kKl) {
    for (const auto& e : query) {
      if (e.second > 0) base += e.second * (std::log(e.second) - kLogEps);
    }
  }
  return base;
}

double bowScoreFinish(ScoringType scoring, double acc, double base) {
  switch (scoring) {
    case ScoringType::kL1:
      return 0.5 * acc;  // = 1 - 0.5 * ||a - b||_1 for L1-unit vectors
    case ScoringType::kL2:
      // Rounding can push <a,b> a hair above 1 for identical vectors.
      return acc >= 1.0 ? 1.0 : 1.0 - std::sqrt(1.0 - acc);
    case ScoringType::kChiSquare:
      return 2.0 * acc;
    case ScoringType::kKl:
      return std::exp(-(base + acc));
    case ScoringType::kBhattacharyya:
    case ScoringType::kDotProduct:
      return acc;
  }
  return 0.0;
}

double scoreBowVectors(ScoringType scoring, const BowVector& a, const BowVector& b) {
  // Merge over the two sorted vectors: only shared words contribute.
  double acc = 0.0;
  auto ia = a.begin();
  auto ib = b.begin();
  while (ia != a.end() && ib != b.end()) {
    if (ia->first < ib->first) {
      ++ia;
    } else if (ib->first < ia->first) {
      ++ib;
    } else {
      acc += bowScoreTerm(scoring, ia->second, ib->second);
      ++ia;
      ++ib;
    }
  }
  return bowScoreFinish(scoring, acc, bowScoreBase(scoring, a));
}

WeightingType weightingTypeFromString(const std::string& s) {
  if (s == "tf_idf") return WeightingType::kTfIdf;
  if (s == "tf") return WeightingType::kTf;
  if (s == "idf") return WeightingType::kIdf;
  if (s == "binary") return WeightingType::kBinary;
  throw std::invalid_argument("unknown weighting type '" + s +
                              "' (expected tf_idf, tf, idf or binary)");
}

ScoringType scoringTypeFromString(const std::string& s) {
  if (s == "l1") return ScoringType::kL1;
  if (s == "l2") return ScoringType::kL2;
  if (s == "chi_square") return ScoringType::kChiSquare;
  if (s == "kl") return ScoringType::kKl;
  if (s == "bhattacharyya") return ScoringType::kBhattacharyya;
  if (s == "dot_product") return ScoringType::kDotProduct;
  throw std::invalid_argument("unknown scoring type '" + s +
                              "' (expected l1, l2, chi_square, kl, bhattacharyya or dot_product)");
}

std::string toString(WeightingType t) {
  switch (t) {
    case WeightingType::kTfIdf: return "tf_idf";
    case WeightingType::kTf: return "tf";
    case WeightingType::kIdf: return "idf";
    case WeightingType::kBinary: return "binary";
  }
  return "unknown";
}

std::string toString(ScoringType t) {
  switch (t) {
    case ScoringType::kL1: return "l1";
    case ScoringType::kL2: return "l2";
    case ScoringType::kChiSquare: return "chi_square";
    case ScoringType::kKl: return "kl";
    case ScoringType::kBhattacharyya: return "bhattacharyya";
    case ScoringType::kDotProduct: return "dot_product";
  }
  return "unknown";
}

}  // namespace bowg
