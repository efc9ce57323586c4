// alignMission against motions worked out by hand: a mission frame turned by
// 90 deg and moved by (1, 2, 0), a wrong loop outvoted, the roll about the
// pipe axis ignored, a yaw near 180 deg not split by the wrap.
#include "bowg_pose_graph/mission_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace bowg {
namespace pose_graph {
namespace {

const double kPi = 3.14159265358979323846;

Eigen::Isometry3d pose(double x, double y, double yaw_deg, double roll_deg = 0) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() = (Eigen::AngleAxisd(yaw_deg * kPi / 180, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(roll_deg * kPi / 180, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  p.translation() = Eigen::Vector3d(x, y, 0);
  return p;
}

double yawDeg(const Eigen::Isometry3d& t) {
  return std::atan2(t.linear()(1, 0), t.linear()(0, 0)) * 180 / kPi;
}

// world_T_mission = yaw 90 deg, t = (1, 2, 0):
//   query (1, 0) heading 0   -> world (0, 1) + (1, 2) = (1, 3), heading 90
//   query (0, 2) heading 90  -> world (-2, 0) + (1, 2) = (-1, 2), heading 180
// A third, wrong loop: query (0, 0) heading 0 at world (10, 10) heading -90
// (yaw -90 about the first loop's 90: -180; translation (10, 10)): the
// medians of {0, 0, -180} and of {1, 1, 10}, {2, 2, 10} keep 90 and (1, 2).
TEST(MissionAlignment, RecoversTheMotionAndOutvotesAWrongLoop) {
  MissionLoopPairs loops(3);
  loops[0] = {pose(1, 0, 0), pose(1, 3, 90)};
  loops[1] = {pose(0, 2, 90), pose(-1, 2, 180)};
  loops[2] = {pose(0, 0, 0), pose(10, 10, -90)};
  const Eigen::Isometry3d t = alignMission(loops);
  EXPECT_NEAR(yawDeg(t), 90.0, 1e-9);
  EXPECT_NEAR(t.translation().x(), 1.0, 1e-9);
  EXPECT_NEAR(t.translation().y(), 2.0, 1e-9);
  EXPECT_NEAR(t.translation().z(), 0.0, 1e-9);
}

// The same place passed with another roll about the pipe axis (the body's
// x): the heading, and so the motion, are unchanged.
TEST(MissionAlignment, TheRollAboutThePipeAxisDoesNotMatter) {
  MissionLoopPairs loops(1);
  loops[0] = {pose(1, 0, 0, 40), pose(1, 3, 90, -25)};
  const Eigen::Isometry3d t = alignMission(loops);
  EXPECT_NEAR(yawDeg(t), 90.0, 1e-9);
  EXPECT_NEAR(t.translation().x(), 1.0, 1e-9);
  EXPECT_NEAR(t.translation().y(), 2.0, 1e-9);
}

// Yaws of 178, 179 and 182 deg (= -178): about the first loop's 178 they are
// 0, 1 and 4 deg, median 1: 179, not the 0 deg a plain median of (-178, 178,
// 179) would give.
TEST(MissionAlignment, AYawNear180DegreesIsNotSplitByTheWrap) {
  MissionLoopPairs loops(3);
  loops[0] = {pose(0, 0, 0), pose(0, 0, 178)};
  loops[1] = {pose(0, 0, 0), pose(0, 0, 179)};
  loops[2] = {pose(0, 0, 0), pose(0, 0, 182)};
  EXPECT_NEAR(yawDeg(alignMission(loops)), 179.0, 1e-9);
}

TEST(MissionAlignment, NoLoopIsRefused) {
  EXPECT_THROW(alignMission(MissionLoopPairs()), std::invalid_argument);
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
