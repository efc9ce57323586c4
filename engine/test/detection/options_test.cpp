// validate() of every stage's options: each rejection names the parameter.
// The ablation rows: ablation_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/detection/detection_options.h"

namespace bowg {
namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Applies `change` to default options and expects validate() to throw an
// InvalidParameter whose message contains `name`.
void expectRejected(const std::function<void(LoopDetectorOptions&)>& change,
                    const std::string& name) {
  LoopDetectorOptions o;
  change(o);
  try {
    o.validate();
    ADD_FAILURE() << "validate() accepted an invalid " << name;
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos)
        << "message '" << e.what() << "' does not name " << name;
  }
}

void expectAccepted(const std::function<void(LoopDetectorOptions&)>& change) {
  LoopDetectorOptions o;
  change(o);
  EXPECT_NO_THROW(o.validate());
}

TEST(Options, DefaultsAreValid) { EXPECT_NO_THROW(LoopDetectorOptions().validate()); }

TEST(Options, WordGroups) {
  expectRejected([](LoopDetectorOptions& o) { o.word_groups.radius_scale = 0; },
                 "word_groups.radius_scale");
  expectRejected([](LoopDetectorOptions& o) { o.word_groups.radius_scale = -1; },
                 "word_groups.radius_scale");
  expectRejected([](LoopDetectorOptions& o) { o.word_groups.radius_scale = kNan; },
                 "word_groups.radius_scale");
  expectRejected([](LoopDetectorOptions& o) { o.word_groups.radius_scale = kInf; },
                 "word_groups.radius_scale");
  expectAccepted([](LoopDetectorOptions& o) { o.word_groups.radius_scale = 2.5; });
}

TEST(Options, Distribution) {
  expectRejected([](LoopDetectorOptions& o) { o.distribution.fan_bins = 0; },
                 "distribution.fan_bins");
  expectRejected([](LoopDetectorOptions& o) { o.distribution.fan_bins = -4; },
                 "distribution.fan_bins");
  expectRejected([](LoopDetectorOptions& o) { o.distribution.fan_bins = 100000; },
                 "distribution.fan_bins");
  expectAccepted([](LoopDetectorOptions& o) { o.distribution.fan_bins = 1; });
}

TEST(Options, SimilarityLambdas) {
  expectRejected([](LoopDetectorOptions& o) { o.similarity.lambda_1 = -0.1; },
                 "similarity.lambda_1");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.lambda_1 = 1.1; },
                 "similarity.lambda_1");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.lambda_1 = kNan; },
                 "similarity.lambda_1");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.lambda_2 = -0.1; },
                 "similarity.lambda_2");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.lambda_2 = kNan; },
                 "similarity.lambda_2");
  // A sum a hair above 1 (as rounding in a GUI or a parameter file can give)
  // must still pass: 0.7 + (0.3 + 1e-15) = 1.000000000000001.
  expectAccepted([](LoopDetectorOptions& o) {
    o.similarity.lambda_1 = 0.7;
    o.similarity.lambda_2 = 0.3 + 1e-15;
    ASSERT_GT(o.similarity.lambda_1 + o.similarity.lambda_2, 1.0);
  });
  expectRejected(
      [](LoopDetectorOptions& o) {
        o.similarity.lambda_1 = 0.7;
        o.similarity.lambda_2 = 0.3 + 1e-9;
      },
      "similarity.lambda_1 + similarity.lambda_2");
  expectAccepted([](LoopDetectorOptions& o) {
    o.similarity.lambda_1 = 1.0;
    o.similarity.lambda_2 = 0.0;
  });
}

TEST(Options, LambdaSumMessage) {
  SimilarityOptions s;
  s.lambda_1 = 0.7;
  s.lambda_2 = 0.5;
  try {
    s.validate();
    ADD_FAILURE() << "lambda_1 + lambda_2 = 1.2 accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(std::string(e.what()),
              "similarity.lambda_1 + similarity.lambda_2 must be <= 1 (got 0.7 + 0.5)");
  }
}

TEST(Options, SimilarityNormalisers) {
  expectRejected([](LoopDetectorOptions& o) { o.similarity.min_word_normaliser = -0.001; },
                 "similarity.min_word_normaliser");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.min_group_normaliser = kNan; },
                 "similarity.min_group_normaliser");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.min_distribution_normaliser = -1; },
                 "similarity.min_distribution_normaliser");
  expectAccepted([](LoopDetectorOptions& o) { o.similarity.min_word_normaliser = 0; });
  expectRejected([](LoopDetectorOptions& o) { o.similarity.normaliser_floor = -0.1; },
                 "similarity.normaliser_floor");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.normaliser_floor = kNan; },
                 "similarity.normaliser_floor");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.normaliser_window = 0; },
                 "similarity.normaliser_window");
  expectAccepted([](LoopDetectorOptions& o) {
    o.similarity.normaliser_floor = 1.0;
    o.similarity.normaliser_window = 1;
  });
}

TEST(Options, TemporalAlignmentAndMissedQueries) {
  expectRejected([](LoopDetectorOptions& o) { o.temporal_score.alignment_window = -1; },
                 "temporal_score.alignment_window");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_score.max_missed_queries = -1; },
                 "temporal_score.max_missed_queries");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_verification.max_missed_queries = -2; },
                 "temporal_verification.max_missed_queries");
  expectAccepted([](LoopDetectorOptions& o) {
    o.temporal_score.alignment_window = 3;
    o.temporal_score.max_missed_queries = 2;
    o.temporal_verification.max_missed_queries = 2;
  });
}

TEST(Options, TemporalScore) {
  expectRejected([](LoopDetectorOptions& o) { o.temporal_score.w_max = 1.0; },
                 "temporal_score.w_max");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_score.w_max = -0.1; },
                 "temporal_score.w_max");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_score.w_max = kNan; },
                 "temporal_score.w_max");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_score.alpha = 0.0; },
                 "temporal_score.alpha");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_score.alpha = -0.2; },
                 "temporal_score.alpha");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_score.alpha = kNan; },
                 "temporal_score.alpha");
  expectAccepted([](LoopDetectorOptions& o) { o.temporal_score.w_max = 0.0; });
  expectAccepted([](LoopDetectorOptions& o) { o.temporal_score.w_max = 0.99; });
}

TEST(Options, Islands) {
  expectRejected([](LoopDetectorOptions& o) { o.islands.min_score = -0.1; }, "islands.min_score");
  expectRejected([](LoopDetectorOptions& o) { o.islands.min_score = kNan; }, "islands.min_score");
  expectRejected([](LoopDetectorOptions& o) { o.islands.recent_exclusion = -1; },
                 "islands.recent_exclusion");
  expectRejected([](LoopDetectorOptions& o) { o.islands.max_intra_island_gap = -1; },
                 "islands.max_intra_island_gap");
  expectRejected([](LoopDetectorOptions& o) { o.islands.min_island_size = 0; },
                 "islands.min_island_size");
  expectAccepted([](LoopDetectorOptions& o) {
    o.islands.min_score = 0;
    o.islands.recent_exclusion = 0;
    o.islands.max_intra_island_gap = 0;
  });
  // The heading gate: an angle of at most 180 degrees, a drift >= 0.
  expectRejected([](LoopDetectorOptions& o) { o.islands.heading_gate_deg = 180.5; },
                 "islands.heading_gate_deg");
  expectRejected([](LoopDetectorOptions& o) { o.islands.heading_gate_deg = -1; },
                 "islands.heading_gate_deg");
  expectRejected([](LoopDetectorOptions& o) { o.islands.heading_gate_drift_deg = kNan; },
                 "islands.heading_gate_drift_deg");
  expectAccepted([](LoopDetectorOptions& o) {
    o.islands.heading_gate_deg = 180;
    o.islands.heading_gate_drift_deg = 0;
  });
}

TEST(Options, TemporalVerification) {
  expectRejected([](LoopDetectorOptions& o) { o.temporal_verification.k = -1; },
                 "temporal_verification.k");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_verification.max_island_distance = -1; },
                 "temporal_verification.max_island_distance");
  expectAccepted([](LoopDetectorOptions& o) { o.temporal_verification.k = 0; });
}

TEST(Options, Geometric) {
  expectRejected([](LoopDetectorOptions& o) { o.geometric.direct_index_level = 0; },
                 "geometric.direct_index_level");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.max_hamming = -1; },
                 "geometric.max_hamming");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.max_hamming = 257; },
                 "geometric.max_hamming");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.max_neighbour_ratio = 0; },
                 "geometric.max_neighbour_ratio");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.max_neighbour_ratio = 1.5; },
                 "geometric.max_neighbour_ratio");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.max_neighbour_ratio = kNan; },
                 "geometric.max_neighbour_ratio");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_threshold_px = 0; },
                 "geometric.ransac_threshold_px");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_threshold_px = kInf; },
                 "geometric.ransac_threshold_px");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_confidence = 1.0; },
                 "geometric.ransac_confidence");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_confidence = 0.0; },
                 "geometric.ransac_confidence");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.min_inliers = 7; },
                 "geometric.min_inliers");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.candidates = 0; },
                 "geometric.candidates");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.rerank_ransacs = -1; },
                 "geometric.rerank_ransacs");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_refits = -1; },
                 "geometric.ransac_refits");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_seed = -1; },
                 "geometric.ransac_seed");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_bound_confidence = -0.1; },
                 "geometric.ransac_bound_confidence");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_bound_confidence = 1.0; },
                 "geometric.ransac_bound_confidence");
  expectRejected([](LoopDetectorOptions& o) { o.geometric.ransac_bound_confidence = std::nan(""); },
                 "geometric.ransac_bound_confidence");
  expectRejected([](LoopDetectorOptions& o) { o.islands.odometry_gate_m = -0.5; },
                 "islands.odometry_gate_m");
  expectRejected([](LoopDetectorOptions& o) { o.islands.odometry_gate_drift = std::nan(""); },
                 "islands.odometry_gate_drift");
  expectRejected([](LoopDetectorOptions& o) { o.islands.odometry_anchor_m = -0.1; },
                 "islands.odometry_anchor_m");
  expectRejected([](LoopDetectorOptions& o) { o.islands.indexed_per_place = -1; },
                 "islands.indexed_per_place");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_verification.hypotheses = 0; },
                 "temporal_verification.hypotheses");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.normaliser_distance_m = -0.1; },
                 "similarity.normaliser_distance_m");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.normaliser_lookback = -1; },
                 "similarity.normaliser_lookback");
  expectRejected([](LoopDetectorOptions& o) { o.similarity.normaliser_lookback_ratio = 0.5; },
                 "similarity.normaliser_lookback_ratio");
  expectRejected([](LoopDetectorOptions& o) { o.temporal_verification.min_step_m = -0.1; },
                 "temporal_verification.min_step_m");
  expectRejected([](LoopDetectorOptions& o) { o.chain.max_missed = -1; }, "chain.max_missed");
  expectRejected([](LoopDetectorOptions& o) { o.chain.max_strays = -1; }, "chain.max_strays");
  expectAccepted([](LoopDetectorOptions& o) {
    o.geometric.candidates = 5;
    o.geometric.rerank_ransacs = 0;
    o.geometric.ransac_bound_confidence = 0.0;  // no bound: OpenCV's 1,000 samples
    o.geometric.min_inliers = 8;
    o.geometric.max_neighbour_ratio = 1.0;
    o.geometric.direct_index_level = 1;
  });
}

TEST(Options, Scoring) {
  expectRejected([](LoopDetectorOptions& o) { o.scoring = static_cast<ScoringType>(17); },
                 "scoring");
  expectAccepted([](LoopDetectorOptions& o) { o.scoring = ScoringType::kDotProduct; });
}

TEST(Options, StageValidateAloneNamesTheStage) {
  TemporalVerificationOptions t;
  t.k = -3;
  try {
    t.validate();
    ADD_FAILURE() << "k = -3 accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_EQ(std::string(e.what()), "temporal_verification.k must be >= 0 (got -3)");
  }
}

}  // namespace
}  // namespace bowg
