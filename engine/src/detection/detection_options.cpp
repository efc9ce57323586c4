// validate() of the detection stage's options and of LoopDetectorOptions
// (detection_options.h).
#include "bowg/detection/detection_options.h"

#include "bowg/core/validation.h"

namespace bowg {

using namespace check;

void IslandOptions::validate() const {
  requireFiniteAtLeast("islands.min_score", min_score, 0.0);
  requireFiniteAtLeast("islands.images_only_score_margin", images_only_score_margin, 0.0);
  requireIntAtLeast("islands.recent_exclusion", recent_exclusion, 0);
  requireFiniteAtLeast("islands.recent_exclusion_m", recent_exclusion_m, 0.0);
  requireFiniteAtLeast("islands.recent_exclusion_odometer_m", recent_exclusion_odometer_m, 0.0);
  requireIntAtLeast("islands.max_intra_island_gap", max_intra_island_gap, 0);
  requireIntAtLeast("islands.min_island_size", min_island_size, 1);
  requireFiniteAtLeast("islands.odometry_gate_m", odometry_gate_m, 0.0);
  requireFiniteAtLeast("islands.odometry_gate_drift", odometry_gate_drift, 0.0);
  requireFiniteAtLeast("islands.odometry_anchor_m", odometry_anchor_m, 0.0);
  requireFiniteAtLeast("islands.heading_gate_deg", heading_gate_deg, 0.0);
  requireFiniteAtLeast("islands.heading_gate_drift_deg", heading_gate_drift_deg, 0.0);
  if (heading_gate_deg > 180.0) {
    fail("islands.heading_gate_deg", "must be at most 180 (degrees)", str(heading_gate_deg));
  }
  requireIntAtLeast("islands.indexed_per_place", indexed_per_place, 0);
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
  if (!(ransac_bound_confidence == 0.0 ||
        (ransac_bound_confidence > 0.0 && ransac_bound_confidence < 1.0))) {
    fail("geometric.ransac_bound_confidence", "must be 0 (no bound) or in (0, 1)",
         str(ransac_bound_confidence));
  }
  requireIntAtLeast("geometric.candidates", candidates, 1);
  requireIntAtLeast("geometric.rerank_ransacs", rerank_ransacs, 0);
  requireIntAtLeast("geometric.ransac_refits", ransac_refits, 0);
  requireIntAtLeast("geometric.ransac_seed", ransac_seed, 0);
}

void VerifiedChainOptions::validate() const {
  requireIntAtLeast("chain.length", length, 0);
  requireIntAtLeast("chain.max_missed", max_missed, 0);
  requireIntAtLeast("chain.max_strays", max_strays, 0);
  requireIntAtLeast("chain.min_unique_inliers", min_unique_inliers, 0);
  requireIntAtLeast("chain.repeated_texture_keyframes", repeated_texture_keyframes, 1);
  requireFiniteAtLeast("chain.repeated_texture_min_m", repeated_texture_min_m, 0.0);
}

void MetricTranslationOptions::validate() const {
  requireFinitePositive("metric.min_baseline_m", min_baseline_m);
  requireFinitePositive("metric.max_baseline_m", max_baseline_m);
  if (max_baseline_m < min_baseline_m) {
    fail("metric.max_baseline_m", "must be >= metric.min_baseline_m", str(max_baseline_m));
  }
  // Six points fix a pose; two more make the RANSAC's inlier count mean something.
  requireIntAtLeast("metric.min_points", min_points, 6);
  requireFiniteAtLeast("metric.odometer_sigma", odometer_sigma, 0.0);
  // A spread needs two samples.
  requireIntAtLeast("metric.covariance_samples", covariance_samples, 2);
  requireFinitePositive("metric.covariance_scale", covariance_scale);
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
  chain.validate();
  metric.validate();
}

}  // namespace bowg
