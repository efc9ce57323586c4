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

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
