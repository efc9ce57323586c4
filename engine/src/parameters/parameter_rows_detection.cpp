// Parameter rows of the detection stage: islands, temporal and geometric
// verification (paper Sec. III-D).
#include <string>
#include <vector>

#include "parameters/parameter_rows.h"

namespace bowg {
namespace parameter_rows {

// One statement per row, in the README table's order: long because the table
// is, and kept in one piece so that the order is visible.
void addDetectionRows(std::vector<Row>* rows) {
  const std::string det = "detector";
  // --- Islands (Sec. III-D).
  rows->push_back(doubleRow("min_score", det, "islands.min_score", 0.0, 10.0, true,
                            BOWG_FIELD(double, detector.islands.min_score),
                            "Acceptance threshold on the final score eta (the paper's second "
                            "alpha)"));
  rows->push_back(doubleRow("images_only_score_margin", det, "islands.images_only_score_margin",
                            0.0, 10.0, false,
                            BOWG_FIELD(double, detector.islands.images_only_score_margin),
                            "Added to min_score for keyframes without odometry (images only): no "
                            "odometry gate stands between a look-alike and acceptance"));
  rows->push_back(intRow("recent_exclusion", det, "islands.recent_exclusion", 0, 1000000, false,
                         BOWG_FIELD(int, detector.islands.recent_exclusion),
                         "The most recent keyframes are never loop candidates"));
  rows->push_back(doubleRow("recent_exclusion_m", det, "islands.recent_exclusion_m", 0.0, 1e6,
                            false, BOWG_FIELD(double, detector.islands.recent_exclusion_m),
                            "The same window in metres driven, used instead when odometry gives "
                            "the keyframes an odometer (0 = keyframes always)"));
  rows->push_back(
      doubleRow("recent_exclusion_odometer_m", det, "islands.recent_exclusion_odometer_m", 0.0, 1e6,
                false, BOWG_FIELD(double, detector.islands.recent_exclusion_odometer_m),
                "The window in metres for keyframes with an odometer but no odometry positions "
                "(0 = recent_exclusion_m)"));
  rows->push_back(intRow("max_intra_island_gap", det, "islands.max_intra_island_gap", 0, 10000,
                         false, BOWG_FIELD(int, detector.islands.max_intra_island_gap),
                         "Candidates whose ids differ by at most this form one island"));
  rows->push_back(intRow("min_island_size", det, "islands.min_island_size", 1, 10000, false,
                         BOWG_FIELD(int, detector.islands.min_island_size),
                         "Islands with fewer members are ignored"));
  rows->push_back(doubleRow("odometry_gate_m", det, "islands.odometry_gate_m", 0.0, 1e6, false,
                            BOWG_FIELD(double, detector.islands.odometry_gate_m),
                            "Odometry gate: with odometry positions, entries farther from the "
                            "query than this plus odometry_gate_drift times the metres driven "
                            "between them are no candidates (0 = no gate)"));
  rows->push_back(doubleRow("odometry_gate_drift", det, "islands.odometry_gate_drift", 0.0, 10.0,
                            false, BOWG_FIELD(double, detector.islands.odometry_gate_drift),
                            "Odometry gate: metres of dead-reckoning error allowed per metre "
                            "driven"));
  rows->push_back(doubleRow("heading_gate_deg", det, "islands.heading_gate_deg", 0.0, 180.0, false,
                            BOWG_FIELD(double, detector.islands.heading_gate_deg),
                            "Heading gate: with odometry orientations, entries the robot faced "
                            "more than this many degrees (plus heading_gate_drift_deg times the "
                            "root of the metres driven between them) away from the query's "
                            "heading are no candidates (0 = no gate)"));
  rows->push_back(doubleRow("heading_gate_drift_deg", det, "islands.heading_gate_drift_deg", 0.0,
                            90.0, false,
                            BOWG_FIELD(double, detector.islands.heading_gate_drift_deg),
                            "Heading gate: degrees of heading error allowed per square root of a "
                            "metre driven"));
  rows->push_back(doubleRow("odometry_anchor_m", det, "islands.odometry_anchor_m", 0.0, 1e6, false,
                            BOWG_FIELD(double, detector.islands.odometry_anchor_m),
                            "Loop-anchored gate: after a loop, entries whose odometry "
                            "displacement from its match differs from the query's since it by "
                            "more than this plus odometry_gate_drift times the metres driven "
                            "are no candidates (0 = off)"));
  rows->push_back(intRow("indexed_per_place", det, "islands.indexed_per_place", 0, 1000000, false,
                         BOWG_FIELD(int, detector.islands.indexed_per_place),
                         "Keyframes a place joined by loops keeps in the inverse index; one whose "
                         "loop makes its place larger is left out (0 = no limit, as DBoW2)"));
  // --- Temporal verification.
  rows->push_back(intRow("temporal_k", det, "temporal_verification.k", 0, 100, true,
                         BOWG_FIELD(int, detector.temporal_verification.k),
                         "k: previous queries whose best islands must agree (0 = off)"));
  rows->push_back(intRow("max_island_distance", det, "temporal_verification.max_island_distance", 0,
                         10000, false,
                         BOWG_FIELD(int, detector.temporal_verification.max_island_distance),
                         "Two islands agree when their id intervals are at most this far apart"));
  rows->push_back(intRow("temporal_max_missed", det, "temporal_verification.max_missed_queries", 0,
                         100, false,
                         BOWG_FIELD(int, detector.temporal_verification.max_missed_queries),
                         "Queries without an island that do not break the temporal chain "
                         "(0 = DLoopDetector: the first one breaks it)"));
  rows->push_back(doubleRow(
      "max_island_distance_m", det, "temporal_verification.max_island_distance_m", 0.0, 100.0,
      false, BOWG_FIELD(double, detector.temporal_verification.max_island_distance_m),
      "With odometry: the previous island moved by the metres driven must "
      "come within this of the current one (0 = max_island_distance in ids)"));
  rows->push_back(intRow("temporal_hypotheses", det, "temporal_verification.hypotheses", 1, 100,
                         false, BOWG_FIELD(int, detector.temporal_verification.hypotheses),
                         "Islands per query followed with their own temporal chains "
                         "(1 = DLoopDetector: the chosen island only)"));
  rows->push_back(
      doubleRow("temporal_min_step_m", det, "temporal_verification.min_step_m", 0.0, 100.0, false,
                BOWG_FIELD(double, detector.temporal_verification.min_step_m),
                "With odometry: a query counts towards the temporal chain only after "
                "this many metres driven since the last one that did (0 = every query)"));
  rows->push_back(boolRow("temporal_linked_places", det, "temporal_verification.linked_places",
                          false, BOWG_FIELD(bool, detector.temporal_verification.linked_places),
                          "An island at a place joined by accepted loops to a chain's island "
                          "continues that chain (false = DLoopDetector)"));
  rows->push_back(boolRow("temporal_anchored_chain", det, "temporal_verification.anchored_chain",
                          false, BOWG_FIELD(bool, detector.temporal_verification.anchored_chain),
                          "An island a loop of the last few metres anchors (odometry_anchor_m) "
                          "passes the temporal verification (false = DLoopDetector)"));
  // --- Geometric verification.
  rows->push_back(boolRow("geometric_verification", det, "geometric.enabled", true,
                          BOWG_FIELD(bool, detector.geometric.enabled),
                          "Ablation switch: fundamental-matrix RANSAC on direct-index "
                          "correspondences"));
  rows->push_back(intRow("direct_index_level", det, "geometric.direct_index_level", 1, 10, true,
                         BOWG_FIELD(int, detector.geometric.direct_index_level),
                         "Vocabulary level of the direct index (1..L; paper Table III: 4 of 6)"));
  rows->push_back(boolRow("exhaustive_matching", det, "geometric.exhaustive", true,
                          BOWG_FIELD(bool, detector.geometric.exhaustive),
                          "Match every feature against every feature instead of using the direct "
                          "index"));
  rows->push_back(intRow("max_hamming", det, "geometric.max_hamming", 0, 256, false,
                         BOWG_FIELD(int, detector.geometric.max_hamming),
                         "Largest Hamming distance of a correspondence (bits of 256)"));
  rows->push_back(doubleRow("max_neighbour_ratio", det, "geometric.max_neighbour_ratio", 0.01, 1.0,
                            false, BOWG_FIELD(double, detector.geometric.max_neighbour_ratio),
                            "Best/second-best distance ratio test for correspondences"));
  rows->push_back(boolRow("native_ransac", det, "geometric.native_ransac", false,
                          BOWG_FIELD(bool, detector.geometric.native_ransac),
                          "Fundamental matrix by the engine's 7-point RANSAC (false = OpenCV's "
                          "findFundamentalMat, the paper's verification)"));
  rows->push_back(intRow("ransac_refits", det, "geometric.ransac_refits", 0, 10, false,
                         BOWG_FIELD(int, detector.geometric.ransac_refits),
                         "Native RANSAC: least-squares refits of each new best model to its "
                         "inliers (0 = plain RANSAC)"));
  rows->push_back(intRow("ransac_seed", det, "geometric.ransac_seed", 0, 1000000, false,
                         BOWG_FIELD(int, detector.geometric.ransac_seed),
                         "RANSAC's sample sequence (0 = the fixed default; evaluate a few to see "
                         "how much a result owes to it)"));
  rows->push_back(doubleRow("ransac_threshold_px", det, "geometric.ransac_threshold_px", 0.1, 100.0,
                            false, BOWG_FIELD(double, detector.geometric.ransac_threshold_px),
                            "RANSAC reprojection threshold (px)"));
  rows->push_back(doubleRow("ransac_confidence", det, "geometric.ransac_confidence", 0.5, 0.9999,
                            false, BOWG_FIELD(double, detector.geometric.ransac_confidence),
                            "RANSAC confidence"));
  rows->push_back(intRow("min_inliers", det, "geometric.min_inliers", 8, 10000, true,
                         BOWG_FIELD(int, detector.geometric.min_inliers),
                         "Accept a loop with at least this many RANSAC inliers"));
  rows->push_back(doubleRow("ransac_bound_confidence", det, "geometric.ransac_bound_confidence",
                            0.0, 0.999999, false,
                            BOWG_FIELD(double, detector.geometric.ransac_bound_confidence),
                            "RANSAC stops after the samples that find a model with min_inliers "
                            "inliers at this confidence (0 = OpenCV's 1,000)"));
  rows->push_back(intRow("verified_candidates", det, "geometric.candidates", 1, 100, false,
                         BOWG_FIELD(int, detector.geometric.candidates),
                         "Geometric re-ranking: verify the best entries of this many top islands "
                         "and keep the one with the most inliers among those with at least "
                         "min_inliers correspondences (1 = the paper)"));
  rows->push_back(intRow("rerank_ransacs", det, "geometric.rerank_ransacs", 0, 100, false,
                         BOWG_FIELD(int, detector.geometric.rerank_ransacs),
                         "Geometric re-ranking: at most this many RANSACs, on the candidates "
                         "with the most correspondences (0 = rank by correspondences, RANSAC "
                         "only the island that passes the temporal verification)"));
  // --- The verified chain: loops no odometry position places.
  rows->push_back(intRow("verified_chain", det, "chain.length", 0, 60, true,
                         BOWG_FIELD(int, detector.chain.length),
                         "A loop no odometry position places needs the verified matches of this "
                         "many previous queries to lead to its match as the robot moved, or to a "
                         "published loop (0 = off: the temporal verification alone)"));
  rows->push_back(intRow("verified_chain_missed", det, "chain.max_missed", 0, 10, false,
                         BOWG_FIELD(int, detector.chain.max_missed),
                         "Queries without a verified match the chain steps over, in a row"));
  rows->push_back(intRow("verified_chain_strays", det, "chain.max_strays", 0, 10, false,
                         BOWG_FIELD(int, detector.chain.max_strays),
                         "With an odometer: queries whose verified matches all lead elsewhere "
                         "the chain steps over, in all; each counts towards "
                         "verified_chain_missed (0, or no odometer: one ends the chain)"));
  rows->push_back(intRow("min_unique_inliers", det, "chain.min_unique_inliers", 0, 10000, true,
                         BOWG_FIELD(int, detector.chain.min_unique_inliers),
                         "Inliers each match of the chain needs on features the robot's recent "
                         "past does not repeat; on average, each at least half, where the "
                         "odometry gate judged the loop's match (0 = no test)"));
  rows->push_back(intRow("repeated_texture_keyframes", det, "chain.repeated_texture_keyframes", 1,
                         100, false, BOWG_FIELD(int, detector.chain.repeated_texture_keyframes),
                         "Recent keyframes whose correspondences with the query mark its "
                         "repeated texture"));
  rows->push_back(doubleRow("repeated_texture_min_m", det, "chain.repeated_texture_min_m", 0.0,
                            100.0, false, BOWG_FIELD(double, detector.chain.repeated_texture_min_m),
                            "They lie from this many metres driven back to recent_exclusion_m "
                            "(odometer), else spread over the recent_exclusion keyframes"));
  // --- Metric translation of a loop (odometry between the match and a neighbour).
  rows->push_back(boolRow("metric_translation", det, "metric.enabled", false,
                          BOWG_FIELD(bool, detector.metric.enabled),
                          "Loop translation in metres from the odometer between the match and a "
                          "neighbour keyframe (needs odometry and intrinsics)"));
  rows->push_back(doubleRow("metric_min_baseline_m", det, "metric.min_baseline_m", 1e-4, 100.0,
                            false, BOWG_FIELD(double, detector.metric.min_baseline_m),
                            "The neighbour is the nearest keyframe at least this far from the "
                            "match (m)"));
  rows->push_back(doubleRow("metric_max_baseline_m", det, "metric.max_baseline_m", 1e-4, 100.0,
                            false, BOWG_FIELD(double, detector.metric.max_baseline_m),
                            "... and at most this far (m): path length stands for displacement "
                            "only over short stretches"));
  rows->push_back(intRow("metric_min_points", det, "metric.min_points", 6, 10000, false,
                         BOWG_FIELD(int, detector.metric.min_points),
                         "Triangulated loop inliers the PnP fit needs and keeps"));
  rows->push_back(doubleRow("metric_odometer_sigma", det, "metric.odometer_sigma", 0.0, 1.0, false,
                            BOWG_FIELD(double, detector.metric.odometer_sigma),
                            "Relative odometer error over the baseline (covariance along t)"));
  rows->push_back(intRow("metric_covariance_samples", det, "metric.covariance_samples", 2, 1000,
                         false, BOWG_FIELD(int, detector.metric.covariance_samples),
                         "Bootstrap resamples the translation's covariance is measured from"));
  rows->push_back(doubleRow("metric_covariance_scale", det, "metric.covariance_scale", 0.01, 1000.0,
                            false, BOWG_FIELD(double, detector.metric.covariance_scale),
                            "Factor on the measured covariance (calibrated: the 95 % ellipsoid "
                            "holds the truth 95 % of the time)"));
}

}  // namespace parameter_rows
}  // namespace bowg
