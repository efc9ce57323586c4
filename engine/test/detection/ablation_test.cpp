// The ablation rows of LoopDetectorOptions (detection/ablation.cpp): the
// paper's module rows, the paper's method as written, the configuration
// without one extension; every other field kept.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/detection/detection_options.h"

namespace bowg {
namespace {

struct Modules {
  bool groups, temporal, distribution;
};

Modules modules(const LoopDetectorOptions& o) {
  return {o.word_groups.enabled, o.temporal_score.enabled, o.distribution.enabled};
}

TEST(Ablation, RowsSwitchOnOneModuleEach) {
  // Start from the opposite of each row to see every switch move.
  LoopDetectorOptions all_on, all_off;
  all_on.word_groups.enabled = all_on.temporal_score.enabled = all_on.distribution.enabled = true;
  all_off.word_groups.enabled = all_off.temporal_score.enabled = false;
  all_off.distribution.enabled = false;

  Modules m = modules(LoopDetectorOptions::ablation("bow", all_on));
  EXPECT_FALSE(m.groups);
  EXPECT_FALSE(m.temporal);
  EXPECT_FALSE(m.distribution);

  m = modules(LoopDetectorOptions::ablation("word_groups", all_on));
  EXPECT_TRUE(m.groups);
  EXPECT_FALSE(m.temporal);
  EXPECT_FALSE(m.distribution);

  m = modules(LoopDetectorOptions::ablation("temporal", all_off));
  EXPECT_TRUE(m.groups);
  EXPECT_TRUE(m.temporal);
  EXPECT_FALSE(m.distribution);

  m = modules(LoopDetectorOptions::ablation("distribution", all_off));
  EXPECT_TRUE(m.groups);
  EXPECT_TRUE(m.temporal);
  EXPECT_TRUE(m.distribution);
}

TEST(Ablation, PaperRowIsTheFullMethodWithoutTheExtensions) {
  LoopDetectorOptions base;
  base.word_groups.enabled = false;
  base.similarity.normaliser_floor = 1.0;
  base.temporal_score.alignment_window = 2;
  base.temporal_score.max_missed_queries = 3;
  base.temporal_verification.max_missed_queries = 1;
  base.geometric.candidates = 10;
  base.temporal_verification.hypotheses = 4;
  base.similarity.normaliser_distance_m = 0.05;
  base.similarity.normaliser_lookback = 8;
  base.temporal_verification.min_step_m = 0.02;
  base.geometric.min_inliers = 25;
  base.temporal_score.alignment_window_m = 0.05;
  base.temporal_verification.max_island_distance_m = 0.1;
  base.islands.recent_exclusion_m = 3.0;
  base.islands.odometry_gate_m = 0.5;
  const LoopDetectorOptions o = LoopDetectorOptions::ablation("paper", base);
  EXPECT_EQ(o.islands.odometry_gate_m, 0.0);
  EXPECT_EQ(o.temporal_score.alignment_window_m, 0.0);
  EXPECT_EQ(o.temporal_verification.max_island_distance_m, 0.0);
  EXPECT_EQ(o.islands.recent_exclusion_m, 3.0);  // the same candidates in every row
  EXPECT_TRUE(o.word_groups.enabled);
  EXPECT_TRUE(o.temporal_score.enabled);
  EXPECT_TRUE(o.distribution.enabled);
  EXPECT_EQ(o.similarity.normaliser_floor, 0.0);
  EXPECT_EQ(o.temporal_score.alignment_window, 0);
  EXPECT_EQ(o.temporal_score.max_missed_queries, 0);
  EXPECT_EQ(o.temporal_verification.max_missed_queries, 0);
  EXPECT_EQ(o.geometric.candidates, 1);
  EXPECT_EQ(o.temporal_verification.hypotheses, 1);
  EXPECT_EQ(o.similarity.normaliser_distance_m, 0.0);
  EXPECT_EQ(o.similarity.normaliser_lookback, 0);
  EXPECT_EQ(o.temporal_verification.min_step_m, 0.0);
  EXPECT_EQ(o.geometric.min_inliers, 25);  // thresholds are the preset's
  const LoopDetectorOptions pb = LoopDetectorOptions::ablation("paper_bow", base);
  EXPECT_FALSE(pb.word_groups.enabled);
  EXPECT_FALSE(pb.temporal_score.enabled);
  EXPECT_FALSE(pb.distribution.enabled);
  EXPECT_EQ(pb.similarity.normaliser_floor, 0.0);
  EXPECT_EQ(pb.temporal_score.alignment_window, 0);
  EXPECT_EQ(pb.geometric.candidates, 1);
  EXPECT_EQ(pb.temporal_verification.hypotheses, 1);
  EXPECT_EQ(pb.similarity.normaliser_distance_m, 0.0);
  EXPECT_EQ(pb.geometric.min_inliers, 25);
  const LoopDetectorOptions as_is = LoopDetectorOptions::ablation("configured", base);
  EXPECT_FALSE(as_is.word_groups.enabled);
  EXPECT_EQ(as_is.geometric.candidates, 10);
  EXPECT_EQ(as_is.temporal_verification.hypotheses, 4);
  EXPECT_EQ(as_is.similarity.normaliser_floor, 1.0);
  // The module rows keep the extensions of the base.
  const LoopDetectorOptions full = LoopDetectorOptions::ablation("distribution", base);
  EXPECT_EQ(full.geometric.candidates, 10);
  EXPECT_EQ(full.temporal_score.alignment_window, 2);
}

// Each "without_<x>" row switches exactly one extension back to the paper's
// version: its own fields change, the other extensions stay as configured.
TEST(Ablation, WithoutRowsSwitchOffOneExtensionEach) {
  LoopDetectorOptions base;
  base.similarity.normaliser_floor = 1.0;
  base.similarity.normaliser_distance_m = 0.03;
  base.similarity.normaliser_lookback = 8;
  base.temporal_score.alignment_window = 1;
  base.temporal_score.alignment_window_m = 0.05;
  base.temporal_verification.max_island_distance_m = 0.1;
  base.temporal_score.max_missed_queries = 1;
  base.temporal_verification.max_missed_queries = 1;
  base.temporal_verification.hypotheses = 3;
  base.temporal_verification.min_step_m = 0.02;
  base.temporal_verification.linked_places = true;
  base.islands.odometry_gate_m = 0.5;
  base.islands.odometry_anchor_m = 0.3;
  base.temporal_verification.anchored_chain = true;
  base.geometric.candidates = 10;
  base.islands.indexed_per_place = 2;
  base.islands.heading_gate_deg = 30;
  // Which extensions are on, in the order of the rows below.
  auto on = [](const LoopDetectorOptions& o) {
    return std::vector<bool>{
        o.similarity.normaliser_floor > 0,
        o.similarity.normaliser_distance_m > 0 || o.similarity.normaliser_lookback > 0,
        o.temporal_score.alignment_window > 0 || o.temporal_score.alignment_window_m > 0 ||
            o.temporal_verification.max_island_distance_m > 0,
        o.temporal_score.max_missed_queries > 0 || o.temporal_verification.max_missed_queries > 0,
        o.temporal_verification.hypotheses > 1,
        o.temporal_verification.min_step_m > 0,
        o.temporal_verification.linked_places,
        o.islands.odometry_gate_m > 0,
        o.islands.odometry_anchor_m > 0,
        o.temporal_verification.anchored_chain,
        o.islands.indexed_per_place > 0,
        o.geometric.ransac_bound_confidence > 0,
        o.geometric.native_ransac,
        o.geometric.candidates > 1,
        o.islands.heading_gate_deg > 0};
  };
  const char* rows[] = {
      "without_floor",          "without_normaliser_distance", "without_alignment",
      "without_missed_queries", "without_hypotheses",          "without_min_step",
      "without_linked_places",  "without_odometry_gate",       "without_loop_anchor",
      "without_anchored_chain", "without_place_index",         "without_ransac_bound",
      "without_native_ransac",  "without_reranking",           "without_heading_gate"};
  const int n = 15;
  ASSERT_EQ(on(base), std::vector<bool>(n, true));
  for (int r = 0; r < n; ++r) {
    std::vector<bool> expected(n, true);
    expected[r] = false;
    // Without the odometry's poses no gate nor the anchored chain can run;
    // without the anchor, not the anchored chain.
    const std::string row = rows[r];
    if (row == "without_odometry_gate") expected[r + 1] = expected[r + 2] = expected[14] = false;
    if (row == "without_loop_anchor") expected[r + 1] = false;
    const LoopDetectorOptions o = LoopDetectorOptions::ablation(rows[r], base);
    EXPECT_EQ(on(o), expected) << rows[r];
    EXPECT_NO_THROW(o.validate()) << rows[r];
  }
  // Every "without" row switches off something the paper row also switches off.
  EXPECT_EQ(on(LoopDetectorOptions::ablation("paper", base)), std::vector<bool>(n, false));
}

TEST(Ablation, KeepsTheOtherFields) {
  LoopDetectorOptions base;
  base.scoring = ScoringType::kL2;
  base.similarity.lambda_1 = 0.25;
  base.distribution.fan_bins = 12;
  base.temporal_score.alpha = 0.7;
  base.islands.min_score = 0.45;
  base.temporal_verification.k = 5;
  base.geometric.min_inliers = 30;
  base.word_groups.radius_scale = 1.5;
  for (const char* row : {"bow", "word_groups", "temporal", "distribution"}) {
    const LoopDetectorOptions o = LoopDetectorOptions::ablation(row, base);
    EXPECT_EQ(o.scoring, ScoringType::kL2) << row;
    EXPECT_DOUBLE_EQ(o.similarity.lambda_1, 0.25) << row;
    EXPECT_EQ(o.distribution.fan_bins, 12) << row;
    EXPECT_DOUBLE_EQ(o.temporal_score.alpha, 0.7) << row;
    EXPECT_DOUBLE_EQ(o.islands.min_score, 0.45) << row;
    EXPECT_EQ(o.temporal_verification.k, 5) << row;
    EXPECT_EQ(o.geometric.min_inliers, 30) << row;
    EXPECT_DOUBLE_EQ(o.word_groups.radius_scale, 1.5) << row;
    EXPECT_NO_THROW(o.validate()) << row;
  }
}

TEST(Ablation, UnknownRowListsTheValidNames) {
  try {
    LoopDetectorOptions::ablation("groups", LoopDetectorOptions());
    ADD_FAILURE() << "unknown row accepted";
  } catch (const InvalidParameter& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("groups"), std::string::npos) << msg;
    for (const char* name : {"bow", "word_groups", "temporal", "distribution"}) {
      EXPECT_NE(msg.find(name), std::string::npos) << msg;
    }
  }
}

}  // namespace
}  // namespace bowg
