// positionError and anchoredTruth against hand-worked values.
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

Eigen::Isometry3d planar(double x, double y, double yaw_deg) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, 0);
  return t;
}

TEST(TrajectoryError, TruthInAnotherWorldFrameIsCarriedOntoTheEstimatesAnchor) {
  // The ground truth's world: the robot starts at (10, 5) heading +y (yaw
  // 90 deg) and drives 1 m forward, then 1 m to its left. The estimate (the
  // odometry's frame) starts at the origin heading +x, so in it the truth
  // is (0, 0), (1, 0), (1, 1).
  const PoseVector truth = {planar(10, 5, 90), planar(10, 6, 90), planar(9, 6, 180)};
  const std::vector<Eigen::Vector3d> at_first = anchoredTruth(truth, 0, planar(0, 0, 0));
  ASSERT_EQ(at_first.size(), 3u);
  EXPECT_TRUE(at_first[0].isApprox(Eigen::Vector3d(0, 0, 0), 1e-12));
  EXPECT_TRUE(at_first[1].isApprox(Eigen::Vector3d(1, 0, 0), 1e-12));
  EXPECT_TRUE(at_first[2].isApprox(Eigen::Vector3d(1, 1, 0), 1e-12));
  // Odometry that over-reads the second leg by 0.5 m: errors 0, 0, 0.5 m.
  const std::vector<Eigen::Vector3d> odometry = {{0, 0, 0}, {1, 0, 0}, {1, 1.5, 0}};
  const TrajectoryError e = positionError(odometry, at_first);
  EXPECT_NEAR(e.rmse, std::sqrt(0.25 / 3), 1e-12);
  EXPECT_NEAR(e.last, 0.5, 1e-12);
  // Anchored at the second pose, taken by the estimate to be (1, 0.2)
  // heading +x: the whole truth shifts by 0.2 m along y.
  const std::vector<Eigen::Vector3d> at_second = anchoredTruth(truth, 1, planar(1, 0.2, 0));
  EXPECT_TRUE(at_second[0].isApprox(Eigen::Vector3d(0, 0.2, 0), 1e-12));
  EXPECT_TRUE(at_second[2].isApprox(Eigen::Vector3d(1, 1.2, 0), 1e-12));
  EXPECT_THROW(anchoredTruth(truth, 3, planar(0, 0, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
