// positionError against hand-worked values.
#include "bowg_pose_graph/trajectory_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace bowg {
namespace pose_graph {
namespace {

TEST(TrajectoryError, RmseMaxAndLastOfThePositionErrors) {
  // Errors 0, 3 and 4 m.
  const std::vector<Eigen::Vector3d> truth = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const std::vector<Eigen::Vector3d> estimate = {{0, 0, 0}, {1, 3, 0}, {2, 0, 4}};
  const TrajectoryError e = positionError(estimate, truth);
  EXPECT_EQ(e.frames, 3u);
  EXPECT_NEAR(e.rmse, std::sqrt((0 + 9 + 16) / 3.0), 1e-12);
  EXPECT_DOUBLE_EQ(e.max, 4.0);
  EXPECT_DOUBLE_EQ(e.last, 4.0);
  EXPECT_THROW(positionError({}, {}), std::invalid_argument);
  EXPECT_THROW(positionError(estimate, {{0, 0, 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
