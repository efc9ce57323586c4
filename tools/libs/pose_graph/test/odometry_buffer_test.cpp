// OdometryBuffer: interpolation worked out by hand, the horizon, time jumps.
#include "bowg_pose_graph/odometry_buffer.h"

#include <gtest/gtest.h>

#include <cmath>

namespace bowg {
namespace pose_graph {
namespace {

Eigen::Isometry3d pose(double x, double yaw_deg) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, 0, 0);
  return t;
}

double yawDeg(const Eigen::Isometry3d& t) {
  return std::atan2(t.linear()(1, 0), t.linear()(0, 0)) * 180 / M_PI;
}

TEST(OdometryBuffer, InterpolatesPositionLinearlyAndRotationSpherically) {
  OdometryBuffer b;
  b.add(10.0, pose(0, 0));
  b.add(11.0, pose(2, 40));
  Eigen::Isometry3d p;
  ASSERT_TRUE(b.at(10.25, &p));
  EXPECT_NEAR(p.translation().x(), 0.5, 1e-12);  // a quarter of the way
  EXPECT_NEAR(yawDeg(p), 10.0, 1e-9);            // a quarter of 40 deg
  ASSERT_TRUE(b.at(11.0, &p));                   // exactly on a sample
  EXPECT_NEAR(p.translation().x(), 2.0, 1e-12);
  EXPECT_FALSE(b.at(9.99, &p));   // before the buffer
  EXPECT_FALSE(b.at(11.01, &p));  // not yet received
}

TEST(OdometryBuffer, ForgetsBeyondTheHorizonAndRestartsWhenTimeGoesBack) {
  OdometryBuffer b(5.0);
  for (int i = 0; i <= 10; ++i) b.add(100.0 + i, pose(i, 0));
  EXPECT_DOUBLE_EQ(b.oldest(), 105.0);  // 110 - 5
  EXPECT_DOUBLE_EQ(b.newest(), 110.0);
  b.add(50.0, pose(0, 0));  // a replay started over
  EXPECT_DOUBLE_EQ(b.oldest(), 50.0);
  EXPECT_DOUBLE_EQ(b.newest(), 50.0);
  EXPECT_THROW(OdometryBuffer(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
