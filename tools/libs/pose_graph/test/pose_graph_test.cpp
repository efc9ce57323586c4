// PoseGraph: least-squares solutions worked out by hand, the robust loss on
// a false loop, bad edges and options.
#include "bowg_pose_graph/pose_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>

namespace bowg {
namespace pose_graph {
namespace {

Eigen::Isometry3d pose(double x, double y, double yaw_deg) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, 0);
  return t;
}

double yawDeg(const Eigen::Isometry3d& t) {
  return std::atan2(t.linear()(1, 0), t.linear()(0, 0)) * 180 / M_PI;
}

/// Equal sigmas everywhere (no step-length term) and no robust loss, so the
/// optimum is the least-squares one.
PoseGraphOptions quadratic() {
  PoseGraphOptions o;
  o.odometry_position_fraction = 0;
  o.odometry_position_floor = 0.1;
  o.odometry_rotation_deg_per_sqrt_m = 0;
  o.odometry_rotation_floor_deg = 1.0;
  o.loop_position_sigma = 0.1;
  o.loop_rotation_sigma_deg = 1.0;
  o.loop_robust_sigmas = 0;
  return o;
}

TEST(PoseGraph, WithoutLoopsTheOdometryChainIsTheOptimum) {
  PoseGraph g;
  g.addPose(pose(0, 0, 0));
  g.addPose(pose(1, 0, 10));
  g.addPose(pose(2, 0.5, 30));
  g.addOdometry(0, 1, pose(0, 0, 0).inverse() * pose(1, 0, 10));
  g.addOdometry(1, 2, pose(1, 0, 10).inverse() * pose(2, 0.5, 30));
  g.optimize();
  EXPECT_NEAR((g.pose(2).translation() - Eigen::Vector3d(2, 0.5, 0)).norm(), 0, 1e-9);
  EXPECT_NEAR(yawDeg(g.pose(2)), 30, 1e-7);
}

/// Two odometry steps of +1 m along x and a loop saying node 2 is where
/// node 0 is (its sigma widened by `extra_sigma`); optimised. The rotations
/// are held by a tight sigma: free, a small yaw of node 1 would trade a
/// little rotation cost for position cost, away from the 1-D optimum.
std::unique_ptr<PoseGraph> lineWithALoop(double extra_sigma, SolveSummary* summary) {
  PoseGraphOptions o = quadratic();
  o.odometry_rotation_floor_deg = 1e-4;
  std::unique_ptr<PoseGraph> g(new PoseGraph(o));
  for (int i = 0; i < 3; ++i) g->addPose(pose(i, 0, 0));
  g->addOdometry(0, 1, pose(1, 0, 0));
  g->addOdometry(1, 2, pose(1, 0, 0));
  LoopEdge loop;
  loop.query = 2;
  loop.match = 0;
  loop.extra_position_sigma = extra_sigma;
  g->addLoop(loop);
  *summary = g->optimize();
  return g;
}

TEST(PoseGraph, ALoopSpreadsTheDisagreementAsLeastSquaresDo) {
  // Minimise (x1 - 1)^2 + (x2 - x1 - 1)^2 + x2^2 (equal sigmas):
  // d/dx1 = 0 -> x2 = 2 x1; d/dx2 = 0 -> 2 x2 - x1 = 1 -> x1 = 1/3, x2 = 2/3.
  SolveSummary s;
  const auto g = lineWithALoop(0.0, &s);
  EXPECT_TRUE(s.converged) << s.report;
  EXPECT_NEAR(g->pose(0).translation().x(), 0, 1e-12);  // the anchor
  EXPECT_NEAR(g->pose(1).translation().x(), 1.0 / 3, 1e-6);
  EXPECT_NEAR(g->pose(2).translation().x(), 2.0 / 3, 1e-6);
  EXPECT_NEAR(g->pose(2).translation().y(), 0, 1e-6);
}

TEST(PoseGraph, ALoopsExtraSigmaWeakensItInQuadrature) {
  // The loop's sigma sqrt(0.1^2 + 0.1^2) = 0.1 sqrt(2): its weight halves.
  // Minimise (x1 - 1)^2 + (x2 - x1 - 1)^2 + x2^2 / 2:
  // x2 = 2 x1 and 1.5 x2 - x1 = 1 -> x1 = 1/2, x2 = 1.
  SolveSummary s;
  const auto g = lineWithALoop(0.1, &s);
  EXPECT_NEAR(g->pose(1).translation().x(), 0.5, 1e-6);
  EXPECT_NEAR(g->pose(2).translation().x(), 1.0, 1e-6);
  LoopEdge bad;
  bad.query = 2;
  bad.extra_position_sigma = -1;
  EXPECT_THROW(g->addLoop(bad), std::invalid_argument);
}

TEST(PoseGraph, ALoopWithARotationSharesTheYawError) {
  // Odometry says +10 deg of yaw, the loop (same sigma) 0 deg: the optimum
  // of (2 sin((a - 10)/2))^2 + (2 sin(a/2))^2 is a = 5 deg.
  PoseGraph g(quadratic());
  g.addPose(pose(0, 0, 0));
  g.addPose(pose(1, 0, 10));
  g.addOdometry(0, 1, pose(1, 0, 10));
  LoopEdge loop;
  loop.query = 1;
  loop.match = 0;
  loop.position = Eigen::Vector3d(1, 0, 0);
  loop.has_rotation = true;
  g.addLoop(loop);
  g.optimize();
  EXPECT_NEAR(yawDeg(g.pose(1)), 5.0, 1e-4);
  // Without the rotation the loop leaves the yaw to the odometry.
  PoseGraph h(quadratic());
  h.addPose(pose(0, 0, 0));
  h.addPose(pose(1, 0, 10));
  h.addOdometry(0, 1, pose(1, 0, 10));
  loop.has_rotation = false;
  h.addLoop(loop);
  h.optimize();
  EXPECT_NEAR(yawDeg(h.pose(1)), 10.0, 1e-4);
}

TEST(PoseGraph, TheRobustLossKeepsAFalseLoopFromBendingTheGraph) {
  // A 40 m straight run, odometry exact; one false loop claims node 40 is
  // at node 0, 40 m away: 267 loop sigmas against 40 odometry edges.
  PoseGraphOptions o;
  o.odometry_position_fraction = 0;
  o.odometry_position_floor = 0.05;
  PoseGraph g(o);
  for (int i = 0; i <= 40; ++i) g.addPose(pose(i, 0, 0));
  for (int i = 0; i < 40; ++i) g.addOdometry(i, i + 1, pose(1, 0, 0));
  LoopEdge wrong;
  wrong.query = 40;
  wrong.match = 0;
  g.addLoop(wrong);
  g.optimize();
  // Robust, the end stays near 40 m; with a quadratic loss the loop's weight
  // (1 / 0.15^2) beats the chain's (1 / (40 x 0.05^2)) and pulls it below 20 m.
  EXPECT_NEAR(g.pose(40).translation().x(), 40.0, 0.5);
  PoseGraphOptions q = o;
  q.loop_robust_sigmas = 0;
  PoseGraph h(q);
  for (int i = 0; i <= 40; ++i) h.addPose(pose(i, 0, 0));
  for (int i = 0; i < 40; ++i) h.addOdometry(i, i + 1, pose(1, 0, 0));
  h.addLoop(wrong);
  h.optimize();
  EXPECT_LT(h.pose(40).translation().x(), 20.0);  // what the loss prevents
}

TEST(PoseGraph, BadEdgesAndOptionsAreRefused) {
  PoseGraph g;
  g.addPose(pose(0, 0, 0));
  EXPECT_THROW(g.addOdometry(0, 1, pose(1, 0, 0)), std::invalid_argument);
  EXPECT_THROW(g.addOdometry(0, 0, pose(1, 0, 0)), std::invalid_argument);
  LoopEdge l;
  l.query = 3;
  EXPECT_THROW(g.addLoop(l), std::invalid_argument);
  PoseGraphOptions o;
  o.loop_position_sigma = 0;
  EXPECT_THROW(PoseGraph{o}, std::invalid_argument);
  o = PoseGraphOptions();
  o.odometry_position_fraction = NAN;
  EXPECT_THROW(PoseGraph{o}, std::invalid_argument);
  o = PoseGraphOptions();
  o.max_iterations = 0;
  EXPECT_THROW(PoseGraph{o}, std::invalid_argument);
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
