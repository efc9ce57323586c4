#include "bowg_pose_graph/loop_translation_error.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace bowg {
namespace pose_graph {
namespace {

LoopEdge edgeAt(double x, double sigma) {
  LoopEdge e;
  e.position = Eigen::Vector3d(x, 0, 0);
  e.has_position_covariance = true;
  e.position_covariance = Eigen::Matrix3d::Identity() * sigma * sigma;
  return e;
}

Eigen::Isometry3d trueAt(double x, double y) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, y, 0);
  return t;
}

TEST(LoopTranslationError, ErrorsBesideTheSamePlaceAssumptionAndTheEllipsoid) {
  // Errors 0.01, 0.02, 0.03, 0.04 (along y); true offsets 0.1 .. 0.4 (along x).
  // Sigmas 0.01 each: e^2 / sigma^2 = 1, 4, 9, 16 -> two of four within 7.815.
  const std::vector<LoopEdge> edges = {edgeAt(0.1, 0.01), edgeAt(0.2, 0.01), edgeAt(0.3, 0.01),
                                       edgeAt(0.4, 0.01)};
  const std::vector<Eigen::Isometry3d> truth = {trueAt(0.1, 0.01), trueAt(0.2, 0.02),
                                                trueAt(0.3, 0.03), trueAt(0.4, 0.04)};
  const LoopTranslationError e = loopTranslationError(edges, truth);
  EXPECT_EQ(e.loops, 4u);
  // Nearest rank: index round(0.5 * 3) = 2 -> 0.03; round(0.9 * 3) = 3 -> 0.04.
  EXPECT_NEAR(e.median, 0.03, 1e-12);
  EXPECT_NEAR(e.p90, 0.04, 1e-12);
  EXPECT_NEAR(e.same_place_median, std::hypot(0.3, 0.03), 1e-12);
  EXPECT_NEAR(e.same_place_p90, std::hypot(0.4, 0.04), 1e-12);
  EXPECT_DOUBLE_EQ(e.inside_95, 0.5);
  EXPECT_THROW(loopTranslationError(edges, {trueAt(0, 0)}), std::invalid_argument);
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
