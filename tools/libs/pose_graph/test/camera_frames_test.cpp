// Camera-to-body frame conversions, worked out by hand.
#include "bowg_pose_graph/camera_frames.h"

#include <gtest/gtest.h>

#include <cmath>

namespace bowg {
namespace pose_graph {
namespace {

TEST(CameraFrames, OpticalAxesInTheBodyFrame) {
  const Eigen::Matrix3d c = bodyFromOptical();
  EXPECT_TRUE((c * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX()));   // forward
  EXPECT_TRUE((c * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY()));  // right
  EXPECT_TRUE((c * Eigen::Vector3d::UnitY()).isApprox(-Eigen::Vector3d::UnitZ()));  // down
  EXPECT_NEAR(c.determinant(), 1.0, 1e-12);
}

TEST(CameraFrames, ARollAboutTheViewingAxisIsARollAboutBodyX) {
  // The match camera rolled +30 deg about the query's optical z: the query
  // is rolled -30 deg in the match's frame, about body x.
  const Eigen::Quaterniond q_R_m(Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitZ()));
  const Eigen::AngleAxisd r(queryInMatchBody(q_R_m));
  EXPECT_NEAR(r.angle(), 30 * M_PI / 180, 1e-12);
  EXPECT_TRUE(r.axis().isApprox(-Eigen::Vector3d::UnitX(), 1e-12));
  // A pan about optical y (down) by +10 deg: about body -z, inverted: +z.
  const Eigen::Quaterniond pan(Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitY()));
  const Eigen::AngleAxisd p(queryInMatchBody(pan));
  EXPECT_NEAR(p.angle(), 10 * M_PI / 180, 1e-12);
  EXPECT_TRUE(p.axis().isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
}

TEST(CameraFrames, ACameraAheadOfTheBodyPutsTheQueryBodyWhereItsCameraStood) {
  // The camera 0.5 m ahead of the body (optical axes as usual); the query
  // passed the place facing the other way: 180 deg about the optical y
  // (down) axis is 180 deg of yaw. Cameras at one place, bodies 0.5 m behind
  // each: the query body lies 1 m ahead of the match body, along its x.
  Eigen::Isometry3d camera = cameraAtBodyOrigin();
  camera.translation() = Eigen::Vector3d(0.5, 0, 0);
  const Eigen::Quaterniond half_turn(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()));
  const LoopEdge e = loopEdgeForCamera(half_turn, camera, true);
  EXPECT_TRUE(e.has_rotation);
  EXPECT_TRUE(e.position.isApprox(Eigen::Vector3d(1, 0, 0), 1e-12)) << e.position.transpose();
  EXPECT_NEAR(Eigen::AngleAxisd(e.rotation).angle(), M_PI, 1e-12);
  EXPECT_EQ(e.extra_position_sigma, 0.0);
  // Same heading: the bodies coincide.
  const LoopEdge same = loopEdgeForCamera(Eigen::Quaterniond::Identity(), camera, true);
  EXPECT_TRUE(same.position.isZero(1e-12));
  // Rotation unknown: position 0, give or take the 0.5 m offset.
  const LoopEdge free = loopEdgeForCamera(half_turn, camera, false);
  EXPECT_FALSE(free.has_rotation);
  EXPECT_TRUE(free.position.isZero());
  EXPECT_DOUBLE_EQ(free.extra_position_sigma, 0.5);
  // At the body's origin, the edge's rotation is queryInMatchBody's.
  const LoopEdge origin = loopEdgeForCamera(half_turn, cameraAtBodyOrigin(), true);
  EXPECT_TRUE(origin.rotation.isApprox(queryInMatchBody(half_turn), 1e-12));
  EXPECT_TRUE(origin.position.isZero(1e-12));
}

TEST(CameraFrames, AMetricLoopPutsTheQueryBodyWhereTheTranslationSays) {
  // Camera at the body's origin, same heading; X_Q = X_M + (0, 0, -0.5):
  // the match camera stood 0.5 m behind the query along the optical z, so
  // the query body is 0.5 m ahead of the match body along body x.
  Eigen::Isometry3d q_T_m = Eigen::Isometry3d::Identity();
  q_T_m.translation() = Eigen::Vector3d(0, 0, -0.5);
  // Optical variances: x (right) 0.01, y (down) 0.04, z (forward) 0.09.
  const Eigen::Matrix3d C = Eigen::Vector3d(0.01, 0.04, 0.09).asDiagonal();
  const LoopEdge e = metricLoopEdge(q_T_m, C, cameraAtBodyOrigin());
  EXPECT_TRUE(e.has_rotation);
  EXPECT_TRUE(e.has_position_covariance);
  EXPECT_TRUE(e.position.isApprox(Eigen::Vector3d(0.5, 0, 0), 1e-12)) << e.position.transpose();
  EXPECT_NEAR(Eigen::AngleAxisd(e.rotation).angle(), 0, 1e-12);
  // In the body: forward (x) 0.09, left (y) 0.01, up (z) 0.04.
  const Eigen::Matrix3d body = Eigen::Vector3d(0.09, 0.01, 0.04).asDiagonal();
  EXPECT_TRUE(e.position_covariance.isApprox(body, 1e-12)) << e.position_covariance;

  // The query turned 90 deg left (yaw) at the match's place, its camera
  // 0.5 m ahead of its body. Query camera axes in the match camera: a yaw
  // left is a turn about optical -y, so q_T_m's rotation (match axes in the
  // query camera) is +90 deg about optical y. Cameras 0.2 m apart along the
  // match's optical x (right): t = R * (-c) with c = (0.2, 0, 0).
  Eigen::Isometry3d camera = cameraAtBodyOrigin();
  camera.translation() = Eigen::Vector3d(0.5, 0, 0);
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
  turned.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  turned.translation() = turned.linear() * Eigen::Vector3d(-0.2, 0, 0);
  const LoopEdge t = metricLoopEdge(turned, Eigen::Matrix3d::Identity() * 1e-4, camera);
  // The query camera stands 0.2 m right of the match camera: 0.5 m ahead of
  // the match body and 0.2 m to its right, (0.5, -0.2, 0). Its body is 0.5 m
  // behind it along its own x, which points to the match body's +y (a left
  // turn): (0.5, -0.2 - 0.5, 0).
  EXPECT_TRUE(t.position.isApprox(Eigen::Vector3d(0.5, -0.7, 0), 1e-12)) << t.position.transpose();
  const Eigen::AngleAxisd yaw(t.rotation);
  EXPECT_NEAR(yaw.angle(), M_PI / 2, 1e-12);
  EXPECT_TRUE(yaw.axis().isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  // An isotropic covariance stays isotropic.
  EXPECT_TRUE(t.position_covariance.isApprox(Eigen::Matrix3d::Identity() * 1e-4, 1e-12));
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
