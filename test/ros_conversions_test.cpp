// ros_conversions: intrinsics, KeyframeFeatures round trip and byte order,
// LoopClosure pose/covariance conventions, KeyframeStatus fields.
#include "bowg_ros/ros_conversions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace bowg_ros {
namespace {

TEST(RosConversions, AnOdometryMessageIsAPositionWithItsHeading) {
  nav_msgs::Odometry msg;
  msg.pose.pose.position.x = 1.5;
  msg.pose.pose.position.y = -2.0;
  msg.pose.pose.position.z = 0.25;
  // Yaw +90 deg about z: the robot faces +y.
  msg.pose.pose.orientation.z = std::sqrt(0.5);
  msg.pose.pose.orientation.w = std::sqrt(0.5);
  const OdometryReading r = toReading(msg);
  EXPECT_EQ(r.source, OdometryReading::kPosition);
  EXPECT_EQ(r.x, 1.5);
  EXPECT_EQ(r.y, -2.0);
  EXPECT_EQ(r.z, 0.25);
  EXPECT_NEAR(r.heading.x, 0.0, 1e-6);
  EXPECT_NEAR(r.heading.y, 1.0, 1e-6);
  EXPECT_NEAR(r.heading.z, 0.0, 1e-6);
  // A driver without orientation leaves it all zero: no heading.
  msg.pose.pose.orientation = geometry_msgs::Quaternion();
  EXPECT_TRUE(toReading(msg).heading.unknown());
  EXPECT_EQ(toReading(msg).x, 1.5);
}

TEST(RosConversions, IntrinsicsFromCameraInfo) {
  sensor_msgs::CameraInfo info;
  EXPECT_FALSE(toIntrinsics(info).valid);  // all-zero K: uncalibrated
  info.K = {300, 0, 160, 0, 310, 120, 0, 0, 1};
  const bowg::CameraIntrinsics k = toIntrinsics(info);
  EXPECT_TRUE(k.valid);
  EXPECT_EQ(k.fx, 300);
  EXPECT_EQ(k.fy, 310);
  EXPECT_EQ(k.cx, 160);
  EXPECT_EQ(k.cy, 120);
  info.K[0] = -1;
  EXPECT_FALSE(toIntrinsics(info).valid);
}

bowg::ImageFeatures twoFeatures() {
  bowg::ImageFeatures f;
  f.image_width = 320;
  f.image_height = 240;
  bowg::Keypoint a;
  a.x = 10.5f;
  a.y = 20.25f;
  a.size = 31;
  a.angle = 45;
  a.response = 0.5f;
  a.octave = 2;
  bowg::Keypoint b = a;
  b.x = 100;
  b.angle = -1;
  f.keypoints = {a, b};
  bowg::Descriptor da, db;
  da.bits = {{0x0807060504030201ull, 0, 0, 0xff00000000000000ull}};
  db.bits = {{~0ull, 1, 2, 3}};
  f.descriptors = {da, db};
  return f;
}

TEST(RosConversions, KeyframeFeaturesUseOpenCvByteOrder) {
  std_msgs::Header h;
  h.frame_id = "cam_optical";
  const KeyframeFeatures msg = toMessage(twoFeatures(), h);
  ASSERT_EQ(msg.descriptors.size(), 64u);
  // Byte j holds bits 8j..8j+7 (types.h): block 0 = 0x0807060504030201 is
  // written low byte first as 01 02 ... 08.
  for (int j = 0; j < 8; ++j) EXPECT_EQ(msg.descriptors[j], j + 1);
  EXPECT_EQ(msg.descriptors[31], 0xff);  // top byte of block 3
  EXPECT_EQ(msg.descriptors[30], 0x00);
  EXPECT_EQ(msg.descriptors[32 + 8], 1);  // second row, block 1 = 1
  EXPECT_EQ(msg.header.frame_id, "cam_optical");
  EXPECT_EQ(msg.image_width, 320u);
}

TEST(RosConversions, KeyframeFeaturesRoundTrip) {
  const bowg::ImageFeatures f = twoFeatures();
  const bowg::ImageFeatures g = fromMessage(toMessage(f, std_msgs::Header()));
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g.image_width, 320);
  EXPECT_EQ(g.image_height, 240);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(g.descriptors[i], f.descriptors[i]);
    EXPECT_EQ(g.keypoints[i].x, f.keypoints[i].x);
    EXPECT_EQ(g.keypoints[i].y, f.keypoints[i].y);
    EXPECT_EQ(g.keypoints[i].size, f.keypoints[i].size);
    EXPECT_EQ(g.keypoints[i].angle, f.keypoints[i].angle);
    EXPECT_EQ(g.keypoints[i].response, f.keypoints[i].response);
    EXPECT_EQ(g.keypoints[i].octave, f.keypoints[i].octave);
  }
}

TEST(RosConversions, InconsistentKeyframeFeaturesAreRejected) {
  const KeyframeFeatures good = toMessage(twoFeatures(), std_msgs::Header());
  KeyframeFeatures m = good;
  m.size.pop_back();
  EXPECT_THROW(fromMessage(m), std::invalid_argument);
  m = good;
  m.descriptors.pop_back();
  EXPECT_THROW(fromMessage(m), std::invalid_argument);
  m = good;
  m.image_width = 0;
  EXPECT_THROW(fromMessage(m), std::invalid_argument);
  bowg::ImageFeatures f = twoFeatures();
  f.descriptors.pop_back();
  EXPECT_THROW(toMessage(f, std_msgs::Header()), std::invalid_argument);
}

// Values the later stages compute with are checked at the input, and the
// image size against the same max_image_pixels as images.
TEST(RosConversions, KeyframeFeaturesWithUnusableValuesAreRejected) {
  const KeyframeFeatures good = toMessage(twoFeatures(), std_msgs::Header());
  KeyframeFeatures m = good;
  m.x[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(fromMessage(m), std::invalid_argument);
  m = good;
  m.size[0] = -1.f;
  EXPECT_THROW(fromMessage(m), std::invalid_argument);
  m = good;
  m.response[0] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(fromMessage(m), std::invalid_argument);
  m = good;
  m.image_width = 30000;
  m.image_height = 30000;
  try {
    fromMessage(m);
    ADD_FAILURE() << "a 30000 x 30000 image accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_image_pixels"), std::string::npos) << e.what();
  }
}

TEST(RosConversions, CovarianceMarksTheScaleUnobservable) {
  const double big = LoopClosure::UNOBSERVABLE_SCALE_VARIANCE;
  double c[36];
  // 15 inliers: sigma = 0.05 * sqrt(15/15) = 0.05 rad -> variance 0.0025.
  fillRelativePoseCovariance(true, 15, nullptr, c);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(c[i * 7], big);
  for (int i = 3; i < 6; ++i) EXPECT_NEAR(c[i * 7], 0.0025, 1e-15);
  // 60 inliers: sigma = 0.05 * sqrt(15/60) = 0.025 -> 0.000625.
  fillRelativePoseCovariance(true, 60, nullptr, c);
  EXPECT_NEAR(c[21], 0.000625, 1e-15);
  for (int r = 0; r < 6; ++r) {
    for (int k = 0; k < 6; ++k) {
      if (r != k) EXPECT_EQ(c[r * 6 + k], 0.0);
    }
  }
  fillRelativePoseCovariance(false, 60, nullptr, c);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(c[i * 7], big);
  // Without a translation block, as downstream code calls it.
  fillRelativePoseCovariance(true, 15, c);
  EXPECT_EQ(c[0], big);
  EXPECT_NEAR(c[21], 0.0025, 1e-15);
}

TEST(RosConversions, CovarianceCarriesTheMetricTranslationsBlock) {
  double c[36];
  const double t[9] = {1e-4, 2e-5, 0, 2e-5, 4e-4, 0, 0, 0, 9e-4};
  fillRelativePoseCovariance(true, 15, t, c);
  EXPECT_EQ(c[0], 1e-4);
  EXPECT_EQ(c[1], 2e-5);
  EXPECT_EQ(c[6], 2e-5);
  EXPECT_EQ(c[7], 4e-4);
  EXPECT_EQ(c[14], 9e-4);
  EXPECT_NEAR(c[21], 0.0025, 1e-15);  // the rotation block as without the scale
  // No pose, no translation: the block says nothing is known.
  fillRelativePoseCovariance(false, 15, t, c);
  EXPECT_EQ(c[0], LoopClosure::UNOBSERVABLE_SCALE_VARIANCE);
  EXPECT_EQ(c[1], 0.0);
}

bowg::LoopResult aLoop() {
  bowg::LoopResult r;
  r.query_id = 42;
  r.status = bowg::LoopStatus::kLoopDetected;
  r.has_candidate = true;
  r.best.entry = 7;
  r.best.eta = 0.9;
  r.best.eta_w = 0.8;
  r.best.eta_g = 0.7;
  r.best.eta_d = 0.6;
  r.best.eta_sim = 0.85;
  r.island_first = 5;
  r.island_last = 9;
  r.island_score = 3.5;
  r.match_id = 7;
  r.match_stamp = 1000.25;
  r.mission = 12;
  r.match_mission = 3;
  r.match_mission_name = "2025-05-12";
  r.correspondences = 50;
  r.inliers = 30;
  bowg::Correspondence c;
  c.query_index = 3;
  c.match_index = 4;
  c.query_x = 1;
  c.query_y = 2;
  c.match_x = 3;
  c.match_y = 4;
  r.inlier_correspondences = {c};
  // 90 degrees about z: R = [0 -1 0; 1 0 0; 0 0 1].
  r.has_relative_pose = true;
  const double R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  std::copy(R, R + 9, r.rotation);
  r.translation_direction[0] = 1;
  return r;
}

TEST(RosConversions, LoopClosureCarriesIdsFramePoseAndOptionalPoints) {
  std_msgs::Header h;
  h.frame_id = "cam_optical";
  h.stamp = ros::Time(2000.5);
  LoopClosure m = toLoopClosure(aLoop(), h, false);
  EXPECT_EQ(m.header.frame_id, "cam_optical");
  EXPECT_EQ(m.query_stamp, h.stamp);
  EXPECT_EQ(m.query_id, 42u);
  EXPECT_EQ(m.match_id, 7u);
  EXPECT_DOUBLE_EQ(m.match_stamp.toSec(), 1000.25);
  EXPECT_EQ(m.query_mission, 12u);
  EXPECT_EQ(m.match_mission, 3u);
  EXPECT_EQ(m.match_mission_name, "2025-05-12");
  EXPECT_EQ(m.score, 0.9);
  EXPECT_EQ(m.score_word, 0.8);
  EXPECT_EQ(m.island_first, 5u);
  EXPECT_EQ(m.island_last, 9u);
  EXPECT_EQ(m.inliers, 30u);
  EXPECT_TRUE(m.has_relative_pose);
  EXPECT_FALSE(m.translation_scale_known);
  // 90 degrees about z: q = (0, 0, sin 45, cos 45).
  const geometry_msgs::Quaternion& q = m.relative_pose.pose.orientation;
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(std::abs(q.z), s, 1e-12);
  EXPECT_NEAR(std::abs(q.w), s, 1e-12);
  EXPECT_GT(q.z * q.w, 0.0);  // same sign: +90, not -90
  EXPECT_NEAR(q.x, 0.0, 1e-12);
  EXPECT_EQ(m.relative_pose.pose.position.x, 1.0);
  EXPECT_EQ(m.relative_pose.covariance[0], LoopClosure::UNOBSERVABLE_SCALE_VARIANCE);
  EXPECT_TRUE(m.query_points.empty());

  m = toLoopClosure(aLoop(), h, true);
  ASSERT_EQ(m.query_indices.size(), 1u);
  EXPECT_EQ(m.query_indices[0], 3u);
  EXPECT_EQ(m.match_indices[0], 4u);
  ASSERT_EQ(m.query_points.size(), 2u);
  EXPECT_EQ(m.query_points[1], 2.0f);
  EXPECT_EQ(m.match_points[0], 3.0f);

  bowg::LoopResult no_pose = aLoop();
  no_pose.has_relative_pose = false;
  m = toLoopClosure(no_pose, h, false);
  EXPECT_FALSE(m.has_relative_pose);
  EXPECT_EQ(m.relative_pose.pose.orientation.w, 1.0);
  EXPECT_EQ(m.relative_pose.pose.position.x, 0.0);
  EXPECT_EQ(m.relative_pose.covariance[35], LoopClosure::UNOBSERVABLE_SCALE_VARIANCE);
}

TEST(RosConversions, AMetricTranslationIsPublishedWithItsCovariance) {
  bowg::LoopResult r = aLoop();
  r.translation_scale_known = true;
  r.translation_m[0] = 0.12;
  r.translation_m[1] = -0.03;
  r.translation_m[2] = 0.04;
  r.translation_covariance[0] = 4e-4;
  r.translation_covariance[8] = 1e-4;
  std_msgs::Header h;
  LoopClosure m = toLoopClosure(r, h, false);
  EXPECT_TRUE(m.translation_scale_known);
  EXPECT_EQ(m.relative_pose.pose.position.x, 0.12);
  EXPECT_EQ(m.relative_pose.pose.position.y, -0.03);
  EXPECT_EQ(m.relative_pose.pose.position.z, 0.04);
  EXPECT_EQ(m.relative_pose.covariance[0], 4e-4);
  EXPECT_EQ(m.relative_pose.covariance[14], 1e-4);
  // Without a pose a scale means nothing.
  r.has_relative_pose = false;
  m = toLoopClosure(r, h, false);
  EXPECT_FALSE(m.translation_scale_known);
  EXPECT_EQ(m.relative_pose.pose.position.x, 0.0);
}

TEST(RosConversions, KeyframeStatusEchoesResultAndOptions) {
  bowg::LoopResult r = aLoop();
  r.timings.total_ms = 4.0;
  r.timings.query_ms = 1.5;
  r.candidates_gated = 6;
  r.candidates_gated_cross_run = 2;
  r.candidates_gated_heading = 3;
  r.mission = 5;
  r.best_mission = 3;
  r.best_mission_name = "2025-05-12";
  r.word_normaliser = 0.05;
  r.word_divisor = 0.08;  // floored
  r.group_divisor = 0.011;
  r.distribution_divisor = 0.97;
  bowg::LoopDetectorOptions o;
  o.similarity.lambda_1 = 0.7;
  o.temporal_verification.k = 5;
  o.distribution.enabled = true;
  const KeyframeStatus s = toKeyframeStatus(r, std_msgs::Header(), o, 321, 43, 0.5, 2.0);
  EXPECT_EQ(s.id, 42u);
  EXPECT_EQ(s.status, KeyframeStatus::LOOP_DETECTED);
  EXPECT_EQ(s.status_text, bowg::toString(bowg::LoopStatus::kLoopDetected));
  EXPECT_EQ(s.num_features, 321u);
  EXPECT_EQ(s.database_size, 43u);
  EXPECT_EQ(s.candidates_gated, 6u);
  EXPECT_EQ(s.candidates_gated_cross_run, 2u);
  EXPECT_EQ(s.candidates_gated_heading, 3u);
  EXPECT_EQ(s.query_mission, 5u);
  EXPECT_EQ(s.best_id, 7u);
  EXPECT_EQ(s.best_mission, 3u);
  EXPECT_EQ(s.best_mission_name, "2025-05-12");
  EXPECT_EQ(s.best_score_sim, 0.85);
  EXPECT_EQ(s.match_id, 7u);
  EXPECT_EQ(s.query_ms, 1.5);
  EXPECT_EQ(s.word_normaliser, 0.05);
  EXPECT_EQ(s.word_divisor, 0.08);
  EXPECT_EQ(s.group_divisor, 0.011);
  EXPECT_EQ(s.distribution_divisor, 0.97);
  EXPECT_EQ(s.total_ms, 4.0 + 0.5 + 2.0);
  EXPECT_EQ(s.lambda_1, 0.7);
  EXPECT_EQ(s.temporal_k, 5);
  EXPECT_TRUE(s.distribution);
  // The message constants follow bowg::LoopStatus.
  EXPECT_EQ(KeyframeStatus::TOO_FEW_INLIERS, static_cast<int>(bowg::LoopStatus::kTooFewInliers));
  EXPECT_EQ(KeyframeStatus::NO_TEMPORAL_CONSISTENCY,
            static_cast<int>(bowg::LoopStatus::kNoTemporalConsistency));
  EXPECT_EQ(KeyframeStatus::NO_FEATURES, static_cast<int>(bowg::LoopStatus::kNoFeatures));
}

}  // namespace
}  // namespace bowg_ros
