// The ablation presets of LoopDetectorOptions (detection_options.h): the
// rows of the paper's ablation study, the paper's method as written, and the
// configuration with one of this implementation's extensions switched off.
#include <string>

#include "bowg/core/errors.h"
#include "bowg/detection/detection_options.h"

namespace bowg {

// One branch per row: long because the list of rows is, and kept in one
// piece so that every row is seen beside the others.
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
    // aligned temporal score, missed-query tolerance, geometric re-ranking,
    // the odometry and heading gates, the verified chain, the place index, RANSAC's
    // sample bound;
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
    o.similarity.normaliser_lookback = 0;
    o.temporal_score.alignment_window = 0;
    o.temporal_score.max_missed_queries = 0;
    o.temporal_verification.max_missed_queries = 0;
    o.temporal_score.alignment_window_m = 0.0;
    o.temporal_verification.max_island_distance_m = 0.0;
    o.temporal_verification.hypotheses = 1;
    o.temporal_verification.min_step_m = 0.0;
    o.temporal_verification.linked_places = false;
    o.temporal_verification.anchored_chain = false;
    o.geometric.candidates = 1;
    o.islands.odometry_gate_m = 0.0;
    o.islands.odometry_anchor_m = 0.0;
    o.islands.heading_gate_deg = 0.0;
    o.chain.length = 0;
    o.islands.indexed_per_place = 0;
    o.geometric.ransac_bound_confidence = 0.0;
    o.geometric.native_ransac = false;
    return o;
  }
  // One extension back to the paper's version, every other field as configured.
  if (row == "without_floor") {
    o.similarity.normaliser_floor = 0.0;
    return o;
  }
  if (row == "without_normaliser_distance") {  // in metres, and looked back without odometry
    o.similarity.normaliser_distance_m = 0.0;
    o.similarity.normaliser_lookback = 0;
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
  if (row == "without_linked_places") {
    o.temporal_verification.linked_places = false;
    return o;
  }
  if (row == "without_odometry_gate") {  // no use of the odometry's poses at all
    o.islands.odometry_gate_m = 0.0;
    o.islands.odometry_anchor_m = 0.0;
    o.islands.heading_gate_deg = 0.0;
    o.temporal_verification.anchored_chain = false;
    return o;
  }
  if (row == "without_heading_gate") {
    o.islands.heading_gate_deg = 0.0;
    return o;
  }
  if (row == "without_loop_anchor") {  // the anchored chain needs the anchor
    o.islands.odometry_anchor_m = 0.0;
    o.temporal_verification.anchored_chain = false;
    return o;
  }
  if (row == "without_anchored_chain") {
    o.temporal_verification.anchored_chain = false;
    return o;
  }
  if (row == "without_place_index") {  // every keyframe indexed, as DBoW2
    o.islands.indexed_per_place = 0;
    return o;
  }
  if (row == "without_ransac_bound") {  // OpenCV's 1,000 RANSAC samples
    o.geometric.ransac_bound_confidence = 0.0;
    return o;
  }
  if (row == "without_native_ransac") {  // OpenCV's findFundamentalMat
    o.geometric.native_ransac = false;
    return o;
  }
  if (row == "without_verified_chain") {  // the temporal verification alone
    o.chain.length = 0;
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
                           "without_linked_places, without_odometry_gate, without_heading_gate, "
                           "without_loop_anchor, "
                           "without_anchored_chain, without_place_index, without_ransac_bound, "
                           "without_native_ransac, without_reranking, without_verified_chain");
  }
  return o;
}

}  // namespace bowg
