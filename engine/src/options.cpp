// validate() of every stage's options and the ablation presets.
//
// Every message starts with "<stage>.<field>" where <stage> is the member name
// in LoopDetectorOptions, so that a user can find the parameter in a launch
// file or dynamic-reconfigure panel without reading the code. Comparisons are
// written so that NaN fails them (e.g. !(x >= 0) instead of x < 0).
#include "bowg/options.h"

#include <cmath>
#include <sstream>

#include "bowg/errors.h"

namespace bowg {
namespace {

// Rounding slack for "lambda_1 + lambda_2 <= 1" (e.g. 0.1 + 0.9).
const double kSumTolerance = 1e-12;

// m above this only costs memory and time: one bin per degree is already finer
// than the angular precision of any corner detector.
const int kMaxFanBins = 360;

template <typename T>
std::string str(T v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

[[noreturn]] void fail(const std::string& name, const std::string& why, const std::string& got) {
  throw InvalidParameter(name + " " + why + " (got " + got + ")");
}

void requireFiniteAtLeast(const std::string& name, double v, double lo) {
  if (!std::isfinite(v) || !(v >= lo)) fail(name, "must be a finite number >= " + str(lo), str(v));
}

void requireFinitePositive(const std::string& name, double v) {
  if (!std::isfinite(v) || !(v > 0.0)) fail(name, "must be a finite number > 0", str(v));
}

void requireUnitInterval(const std::string& name, double v) {
  if (!(v >= 0.0 && v <= 1.0)) fail(name, "must be in [0, 1]", str(v));
}

void requireIntAtLeast(const std::string& name, int v, int lo) {
  if (v < lo) fail(name, "must be >= " + str(lo), str(v));
}

}  // namespace

void WordGroupOptions::validate() const {
  requireFinitePositive("word_groups.radius_scale", radius_scale);
}

void DistributionOptions::validate() const {
  if (fan_bins < 1 || fan_bins > kMaxFanBins) {
    fail("distribution.fan_bins", "must be in [1, " + str(kMaxFanBins) + "]", str(fan_bins));
  }
}

void SimilarityOptions::validate() const {
  requireUnitInterval("similarity.lambda_1", lambda_1);
  requireUnitInterval("similarity.lambda_2", lambda_2);
  // Eq. 9 gives eta_d the weight 1 - l1 - l2, which must not be negative.
  // Checked even with the distribution off, as the header documents, so that
  // switching the distribution on live can never make the options invalid.
  if (lambda_1 + lambda_2 > 1.0 + kSumTolerance) {
    throw InvalidParameter("similarity.lambda_1 + similarity.lambda_2 must be <= 1 (got " +
                           str(lambda_1) + " + " + str(lambda_2) + ")");
  }
  requireFiniteAtLeast("similarity.min_word_normaliser", min_word_normaliser, 0.0);
  requireFiniteAtLeast("similarity.min_group_normaliser", min_group_normaliser, 0.0);
  requireFiniteAtLeast("similarity.min_distribution_normaliser", min_distribution_normaliser, 0.0);
  requireFiniteAtLeast("similarity.normaliser_floor", normaliser_floor, 0.0);
  requireIntAtLeast("similarity.normaliser_window", normaliser_window, 1);
  requireFiniteAtLeast("similarity.normaliser_distance_m", normaliser_distance_m, 0.0);
}

void TemporalScoreOptions::validate() const {
  // w_max = 1 would let the previous score replace the current one entirely
  // when both are equal (eq. 6 -> w_prev = 1), freezing the score.
  if (!(w_max >= 0.0 && w_max < 1.0)) fail("temporal_score.w_max", "must be in [0, 1)", str(w_max));
  requireFinitePositive("temporal_score.alpha", alpha);
  requireIntAtLeast("temporal_score.alignment_window", alignment_window, 0);
  requireIntAtLeast("temporal_score.max_missed_queries", max_missed_queries, 0);
  requireFiniteAtLeast("temporal_score.alignment_window_m", alignment_window_m, 0.0);
}

void IslandOptions::validate() const {
  requireFiniteAtLeast("islands.min_score", min_score, 0.0);
  requireIntAtLeast("islands.recent_exclusion", recent_exclusion, 0);
  requireFiniteAtLeast("islands.recent_exclusion_m", recent_exclusion_m, 0.0);
  requireIntAtLeast("islands.max_intra_island_gap", max_intra_island_gap, 0);
  requireIntAtLeast("islands.min_island_size", min_island_size, 1);
}

void TemporalVerificationOptions::validate() const {
  requireIntAtLeast("temporal_verification.k", k, 0);
  requireIntAtLeast("temporal_verification.max_island_distance", max_island_distance, 0);
  requireIntAtLeast("temporal_verification.max_missed_queries", max_missed_queries, 0);
  requireFiniteAtLeast("temporal_verification.max_island_distance_m", max_island_distance_m, 0.0);
  requireIntAtLeast("temporal_verification.hypotheses", hypotheses, 1);
  requireFiniteAtLeast("temporal_verification.min_step_m", min_step_m, 0.0);
}

void GeometricVerificationOptions::validate() const {
  // The upper bound (the vocabulary depth L) is only known to the Database.
  requireIntAtLeast("geometric.direct_index_level", direct_index_level, 1);
  if (max_hamming < 0 || max_hamming > 256) {
    fail("geometric.max_hamming", "must be in [0, 256] (256-bit descriptors)", str(max_hamming));
  }
  if (!(max_neighbour_ratio > 0.0 && max_neighbour_ratio <= 1.0)) {
    fail("geometric.max_neighbour_ratio", "must be in (0, 1]", str(max_neighbour_ratio));
  }
  requireFinitePositive("geometric.ransac_threshold_px", ransac_threshold_px);
  if (!(ransac_confidence > 0.0 && ransac_confidence < 1.0)) {
    fail("geometric.ransac_confidence", "must be in (0, 1)", str(ransac_confidence));
  }
  // The 8-point algorithm needs 8 correspondences; fewer inliers prove nothing.
  requireIntAtLeast("geometric.min_inliers", min_inliers, 8);
  requireIntAtLeast("geometric.candidates", candidates, 1);
}

void LoopDetectorOptions::validate() const {
  const int s = static_cast<int>(scoring);
  if (s < static_cast<int>(ScoringType::kL1) || s > static_cast<int>(ScoringType::kDotProduct)) {
    fail("scoring", "must be one of l1, l2, chi_square, kl, bhattacharyya, dot_product", str(s));
  }
  word_groups.validate();
  distribution.validate();
  similarity.validate();
  temporal_score.validate();
  islands.validate();
  temporal_verification.validate();
  geometric.validate();
}

LoopDetectorOptions LoopDetectorOptions::ablation(const std::string& row,
                                                  const LoopDetectorOptions& base) {
  // Rows of the paper's ablation study (Sec. IV): each switches on one more
  // module on top of the previous row; every other field is kept from base.
  LoopDetectorOptions o = base;
  if (row == "configured") return o;  // the configuration as it is
  if (row == "paper" || row == "paper_bow") {
    // The paper's method as written (every module on) or the same pipeline
    // with pure bag-of-words scores (DBoW2 + DLoopDetector's islands and
    // checks): every extension of this implementation off (normaliser floor,
    // aligned temporal score, missed-query tolerance, geometric re-ranking;
    // docs/method.md). The configuration's
    // thresholds and its recent-exclusion window (the "immediate past", in
    // metres where odometry is given) are kept: every row is judged on the
    // same candidates.
    const bool all = row == "paper";
    o.word_groups.enabled = all;
    o.temporal_score.enabled = all;
    o.distribution.enabled = all;
    o.similarity.normaliser_floor = 0.0;
    o.similarity.normaliser_distance_m = 0.0;
    o.temporal_score.alignment_window = 0;
    o.temporal_score.max_missed_queries = 0;
    o.temporal_verification.max_missed_queries = 0;
    o.temporal_score.alignment_window_m = 0.0;
    o.temporal_verification.max_island_distance_m = 0.0;
    o.temporal_verification.hypotheses = 1;
    o.temporal_verification.min_step_m = 0.0;
    o.geometric.candidates = 1;
    return o;
  }
  // One extension back to the paper's version, every other field as configured.
  if (row == "without_floor") {
    o.similarity.normaliser_floor = 0.0;
    return o;
  }
  if (row == "without_normaliser_distance") {
    o.similarity.normaliser_distance_m = 0.0;
    return o;
  }
  if (row == "without_alignment") {
    o.temporal_score.alignment_window = 0;
    o.temporal_score.alignment_window_m = 0.0;
    o.temporal_verification.max_island_distance_m = 0.0;
    return o;
  }
  if (row == "without_missed_queries") {
    o.temporal_score.max_missed_queries = 0;
    o.temporal_verification.max_missed_queries = 0;
    return o;
  }
  if (row == "without_hypotheses") {
    o.temporal_verification.hypotheses = 1;
    return o;
  }
  if (row == "without_min_step") {
    o.temporal_verification.min_step_m = 0.0;
    return o;
  }
  if (row == "without_reranking") {
    o.geometric.candidates = 1;
    return o;
  }
  if (row == "bow") {
    o.word_groups.enabled = false;
    o.temporal_score.enabled = false;
    o.distribution.enabled = false;
  } else if (row == "word_groups") {
    o.word_groups.enabled = true;
    o.temporal_score.enabled = false;
    o.distribution.enabled = false;
  } else if (row == "temporal") {
    o.word_groups.enabled = true;
    o.temporal_score.enabled = true;
    o.distribution.enabled = false;
  } else if (row == "distribution") {
    o.word_groups.enabled = true;
    o.temporal_score.enabled = true;
    o.distribution.enabled = true;
  } else {
    throw InvalidParameter("ablation row '" + row +
                           "' is unknown; valid rows: bow, word_groups, temporal, distribution, "
                           "paper_bow, paper, configured, without_floor, "
                           "without_normaliser_distance, without_alignment, "
                           "without_missed_queries, without_hypotheses, without_min_step, "
                           "without_reranking");
  }
  return o;
}

}  // namespace bowg
