// Parameter rows of the scoring stage: metric, word groups, distribution,
// similarity and normalisation, temporal score (paper Secs. III-A to III-C).
#include <string>
#include <vector>

#include "bowg/vocabulary/bow_vector.h"
#include "parameters/parameter_rows.h"

namespace bowg {
namespace parameter_rows {

// One statement per row, in the README table's order: long because the table
// is, and kept in one piece so that the order is visible.
void addScoringRows(std::vector<Row>* rows) {
  const std::string det = "detector";
  // --- Scoring (paper Sec. III-B, DBoW2's metrics).
  rows->push_back(enumRow(
      "scoring", det, "scoring", {"l1", "l2", "chi_square", "kl", "bhattacharyya", "dot_product"},
      [](PipelineOptions* o, const std::string& v) {
        o->detector.scoring = scoringTypeFromString(v);
      },
      [](const PipelineOptions& o) { return toString(o.detector.scoring); },
      "Word-score metric s_w (DBoW2 numbering); a run-time choice, independent of the "
      "vocabulary file"));
  // --- Word groups (Sec. III-A).
  rows->push_back(boolRow("word_groups", det, "word_groups.enabled", true,
                          BOWG_FIELD(bool, detector.word_groups.enabled),
                          "Ablation switch: word groups and the group score eta_g (off = pure "
                          "bag of words)"));
  rows->push_back(doubleRow("group_radius_scale", det, "word_groups.radius_scale", 0.01, 10.0,
                            false, BOWG_FIELD(double, detector.word_groups.radius_scale),
                            "A neighbour joins a word group when closer than this times the "
                            "keypoint size (paper: 1)"));
  // --- Distribution score (Sec. III-C).
  rows->push_back(boolRow("distribution", det, "distribution.enabled", true,
                          BOWG_FIELD(bool, detector.distribution.enabled),
                          "Ablation switch: the roll-invariant feature-distribution score eta_d "
                          "(on in pipes, off for generic scenes)"));
  rows->push_back(
      intRow("fan_bins", det, "distribution.fan_bins", 1, 64, true,
             BOWG_FIELD(int, detector.distribution.fan_bins),
             "m: number of fan-shaped bins of angle 2*pi/m around the principal point"));
  // --- Similarity (eqs. 2-5, 9).
  rows->push_back(doubleRow("lambda_1", det, "similarity.lambda_1", 0.0, 1.0, true,
                            BOWG_FIELD(double, detector.similarity.lambda_1),
                            "lambda_1: weight of the normalised word score eta_w (eqs. 5, 9)"));
  rows->push_back(doubleRow("lambda_2", det, "similarity.lambda_2", 0.0, 1.0, true,
                            BOWG_FIELD(double, detector.similarity.lambda_2),
                            "lambda_2: weight of eta_g when the distribution score is on (eq. 9); "
                            "lambda_1 + lambda_2 <= 1"));
  rows->push_back(doubleRow("min_word_normaliser", det, "similarity.min_word_normaliser", 0.0, 1.0,
                            false, BOWG_FIELD(double, detector.similarity.min_word_normaliser),
                            "No loop when s_w(I_t, I_t-1) is below this (DLoopDetector's "
                            "min_nss_factor)"));
  rows->push_back(doubleRow("min_group_normaliser", det, "similarity.min_group_normaliser", 0.0,
                            1.0, false,
                            BOWG_FIELD(double, detector.similarity.min_group_normaliser),
                            "No loop when s_g(I_t, I_t-1) is below this"));
  rows->push_back(doubleRow("min_distribution_normaliser", det,
                            "similarity.min_distribution_normaliser", 0.0, 1.0, false,
                            BOWG_FIELD(double, detector.similarity.min_distribution_normaliser),
                            "No loop when s_d(I_t, I_t-1) is below this"));
  rows->push_back(doubleRow("normaliser_floor", det, "similarity.normaliser_floor", 0.0, 10.0,
                            false, BOWG_FIELD(double, detector.similarity.normaliser_floor),
                            "Each normaliser is at least this times the median normaliser of the "
                            "last normaliser_window keyframes (0 = the paper's s(I_t, I_t-1) "
                            "alone; docs/method.md)"));
  rows->push_back(intRow("normaliser_window", det, "similarity.normaliser_window", 1, 100000, false,
                         BOWG_FIELD(int, detector.similarity.normaliser_window),
                         "Keyframes in the median of the normaliser floor"));
  rows->push_back(doubleRow("normaliser_distance_m", det, "similarity.normaliser_distance_m", 0.0,
                            100.0, false,
                            BOWG_FIELD(double, detector.similarity.normaliser_distance_m),
                            "With odometry: normalise by the score against the newest keyframe "
                            "driven at least this far back instead of I_t-1 (0 = I_t-1 always)"));
  rows->push_back(intRow("normaliser_lookback", det, "similarity.normaliser_lookback", 0, 1000,
                         false, BOWG_FIELD(int, detector.similarity.normaliser_lookback),
                         "Without odometry: normalise by the newest of this many keyframes back "
                         "that looks no more like the query than the median I_t-1 does (a robot "
                         "that slowed down; 0 = I_t-1 always)"));
  rows->push_back(doubleRow("normaliser_lookback_ratio", det,
                            "similarity.normaliser_lookback_ratio", 1.0, 100.0, false,
                            BOWG_FIELD(double, detector.similarity.normaliser_lookback_ratio),
                            "The lookback starts where s(I_t, I_t-1) exceeds this times the "
                            "median (a robot that slowed down, not one keyframe's noise)"));
  // --- Temporal score (eqs. 6-7).
  rows->push_back(boolRow("temporal_score", det, "temporal_score.enabled", true,
                          BOWG_FIELD(bool, detector.temporal_score.enabled),
                          "Ablation switch: the adaptive temporal score eta_temp (eqs. 6-7)"));
  rows->push_back(doubleRow("w_max", det, "temporal_score.w_max", 0.0, 0.99, true,
                            BOWG_FIELD(double, detector.temporal_score.w_max),
                            "w_max: largest weight of the previous query's score (eq. 6)"));
  rows->push_back(doubleRow("alpha", det, "temporal_score.alpha", 0.001, 10.0, true,
                            BOWG_FIELD(double, detector.temporal_score.alpha),
                            "alpha: scale of the score difference in eq. 6 (not the acceptance "
                            "threshold, see min_score)"));
  rows->push_back(intRow("alignment_window", det, "temporal_score.alignment_window", 0, 1000, false,
                         BOWG_FIELD(int, detector.temporal_score.alignment_window),
                         "r: eq. 7's previous score is the best of the previous query's scores "
                         "of entries tj-1-r .. tj-1+r, so passes at different speeds keep it "
                         "(0 = eq. 7 exactly; docs/method.md)"));
  rows->push_back(intRow("temporal_memory", det, "temporal_score.max_missed_queries", 0, 100, false,
                         BOWG_FIELD(int, detector.temporal_score.max_missed_queries),
                         "Queries that cannot be scored (no candidate, small normaliser) that "
                         "eq. 7's previous scores survive (0 = the paper: forgotten at once)"));
  rows->push_back(doubleRow("alignment_window_m", det, "temporal_score.alignment_window_m", 0.0,
                            100.0, false,
                            BOWG_FIELD(double, detector.temporal_score.alignment_window_m),
                            "With odometry: eq. 7's previous score is the best among the entries "
                            "within this many metres of where tj was when the previous query was "
                            "taken (0 = alignment_window in keyframes)"));
}

}  // namespace parameter_rows
}  // namespace bowg
