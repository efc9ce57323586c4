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

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
