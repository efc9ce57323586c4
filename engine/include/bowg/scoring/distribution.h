// Feature-distribution score (paper Sec. III-C, eqs. 8-9; reading fixed in
// docs/method.md (step 5): best alignment over cyclic shifts, not the largest
// distance).
#pragma once

#include <cstddef>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

/// Fan bin of a point: the angle of (x - cx, y - cy), measured with atan2 in
/// image coordinates and wrapped to [0, 2*pi), falls in bin
/// k = floor(angle / (2*pi/m)), bin k starting at phi_k = 2*pi*k/m.
/// A point exactly at the centre goes to bin 0. Requires m >= 1.
int fanBin(float x, float y, double cx, double cy, int m);

/// v = [n_0 .. n_{m-1}] counts of keypoints per fan bin, L2-normalised
/// (all zeros when there are no keypoints).
std::vector<double> distributionVector(const std::vector<ImagePoint>& points, double cx, double cy,
                                       int m);

/// s_d = max over i of <M_i^query, v_db>, M_i the query vector cyclically
/// shifted by i (m_ij = v_((i+j) mod m)). Sizes must match (throws
/// std::invalid_argument otherwise). In [0, 1] for non-negative unit vectors.
double distributionScore(const std::vector<double>& query, const std::vector<double>& db);

/// distributionScore(query, db) for many db vectors of one query (a database
/// query scores every entry it reaches): the query's cyclic shifts are laid
/// out once, not once per vector. One per query and thread.
class DistributionScorer {
 public:
  /// `db_bins`: the length of every vector it will score; throws
  /// std::invalid_argument naming `caller` when the query's differs (the two
  /// were built with different numbers of fan bins).
  DistributionScorer(const std::vector<double>& query, std::size_t db_bins, const char* caller);
  /// Scores nothing (bins() 0): a query that asks for no distribution score.
  DistributionScorer() = default;
  std::size_t bins() const { return dots_.size(); }
  /// The score against the bins() values at `db`, bit for bit
  /// distributionScore's.
  double score(const double* db);

 private:
  std::vector<double> twice_;  ///< the query twice over: shift i starts at i
  std::vector<double> dots_;   ///< one dot product per shift
};

}  // namespace bowg
