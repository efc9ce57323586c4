// Engine types <-> ROS messages (see ros_conversions.h).
#include "bowg_ros/ros_conversions.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "bowg/core/odometry_heading.h"
#include "bowg/features/descriptor_conversion.h"
#include "bowg/features/feature_arrays.h"

namespace bowg_ros {

OdometryReading toReading(const nav_msgs::Odometry& msg) {
  const geometry_msgs::Point& p = msg.pose.pose.position;
  const geometry_msgs::Quaternion& q = msg.pose.pose.orientation;
  return OdometryReading::position(p.x, p.y, p.z, bowg::headingFromQuaternion(q.x, q.y, q.z, q.w));
}

bowg::CameraIntrinsics toIntrinsics(const sensor_msgs::CameraInfo& info) {
  bowg::CameraIntrinsics k;
  k.fx = info.K[0];
  k.fy = info.K[4];
  k.cx = info.K[2];
  k.cy = info.K[5];
  k.valid = k.fx > 0.0 && k.fy > 0.0 && std::isfinite(k.fx) && std::isfinite(k.fy) &&
            std::isfinite(k.cx) && std::isfinite(k.cy);
  return k;
}

bowg::ImageFeatures fromMessage(const KeyframeFeatures& msg, const bowg::FeatureOptions& options) {
  static_assert(KeyframeFeatures::DESCRIPTOR_BYTES == bowg::kDescriptorBytes,
                "the message's descriptor rows are the engine's");
  bowg::FeatureArrays a;
  a.image_width = msg.image_width;
  a.image_height = msg.image_height;
  a.x = msg.x;
  a.y = msg.y;
  a.size = msg.size;
  a.angle = msg.angle;
  a.response = msg.response;
  a.octave = msg.octave;
  a.descriptors = msg.descriptors;
  return bowg::featuresFromArrays(a, options);
}

KeyframeFeatures toMessage(const bowg::ImageFeatures& features, const std_msgs::Header& header) {
  if (features.keypoints.size() != features.descriptors.size()) {
    throw std::invalid_argument("ImageFeatures: keypoints and descriptors differ in number");
  }
  KeyframeFeatures msg;
  msg.header = header;
  msg.image_width = static_cast<std::uint32_t>(features.image_width);
  msg.image_height = static_cast<std::uint32_t>(features.image_height);
  const std::size_t n = features.size();
  msg.x.reserve(n);
  msg.y.reserve(n);
  msg.size.reserve(n);
  msg.angle.reserve(n);
  msg.response.reserve(n);
  msg.octave.reserve(n);
  msg.descriptors.resize(n * KeyframeFeatures::DESCRIPTOR_BYTES);
  for (std::size_t i = 0; i < n; ++i) {
    const bowg::Keypoint& k = features.keypoints[i];
    msg.x.push_back(k.x);
    msg.y.push_back(k.y);
    msg.size.push_back(k.size);
    msg.angle.push_back(k.angle);
    msg.response.push_back(k.response);
    msg.octave.push_back(k.octave);
    bowg::descriptorToBytes(features.descriptors[i], &msg.descriptors[i * bowg::kDescriptorBytes]);
  }
  return msg;
}

void fillRelativePoseCovariance(bool has_pose, int inliers, const double* translation_covariance,
                                double* c) {
  const double big = LoopClosure::UNOBSERVABLE_SCALE_VARIANCE;
  for (int i = 0; i < 36; ++i) c[i] = 0.0;
  for (int i = 0; i < 3; ++i) c[i * 7] = big;
  if (has_pose && translation_covariance) {
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) c[r * 6 + k] = translation_covariance[r * 3 + k];
    }
  }
  double rotation_variance = big;
  if (has_pose && inliers > 0) {
    // 0.05 rad (about 3 degrees) at the default min_inliers = 15, shrinking
    // as 1/sqrt(n): a heuristic, documented in LoopClosure.msg.
    const double sigma = 0.05 * std::sqrt(15.0 / inliers);
    rotation_variance = sigma * sigma;
  }
  for (int i = 3; i < 6; ++i) c[i * 7] = rotation_variance;
}

LoopClosure toLoopClosure(const bowg::LoopResult& r, const std_msgs::Header& header,
                          bool with_correspondences) {
  LoopClosure msg;
  msg.header = header;
  msg.query_id = r.query_id;
  msg.query_stamp = header.stamp;
  msg.match_id = r.match_id;
  msg.match_stamp = ros::Time(r.match_stamp);
  msg.query_mission = r.mission;
  msg.match_mission = r.match_mission;
  msg.match_mission_name = r.match_mission_name;
  msg.score = r.best.eta;
  msg.score_word = r.best.eta_w;
  msg.score_group = r.best.eta_g;
  msg.score_distribution = r.best.eta_d;
  msg.island_first = r.island_first;
  msg.island_last = r.island_last;
  msg.island_score = r.island_score;
  msg.correspondences = static_cast<std::uint32_t>(std::max(0, r.correspondences));
  msg.inliers = static_cast<std::uint32_t>(std::max(0, r.inliers));
  msg.has_relative_pose = r.has_relative_pose;
  msg.translation_scale_known = r.has_relative_pose && r.translation_scale_known;
  geometry_msgs::Pose& pose = msg.relative_pose.pose;
  pose.orientation.w = 1.0;
  if (r.has_relative_pose) {
    Eigen::Matrix3d R;
    R << r.rotation[0], r.rotation[1], r.rotation[2], r.rotation[3], r.rotation[4], r.rotation[5],
        r.rotation[6], r.rotation[7], r.rotation[8];
    Eigen::Quaterniond q(R);
    q.normalize();
    pose.orientation.x = q.x();
    pose.orientation.y = q.y();
    pose.orientation.z = q.z();
    pose.orientation.w = q.w();
    const double* t = msg.translation_scale_known ? r.translation_m : r.translation_direction;
    pose.position.x = t[0];
    pose.position.y = t[1];
    pose.position.z = t[2];
  }
  fillRelativePoseCovariance(r.has_relative_pose, r.inliers,
                             msg.translation_scale_known ? r.translation_covariance : nullptr,
                             msg.relative_pose.covariance.data());
  if (with_correspondences) {
    for (const bowg::Correspondence& c : r.inlier_correspondences) {
      msg.query_indices.push_back(c.query_index);
      msg.match_indices.push_back(c.match_index);
      msg.query_points.push_back(c.query_x);
      msg.query_points.push_back(c.query_y);
      msg.match_points.push_back(c.match_x);
      msg.match_points.push_back(c.match_y);
    }
  }
  return msg;
}

KeyframeStatus toKeyframeStatus(const bowg::LoopResult& r, const std_msgs::Header& header,
                                const bowg::LoopDetectorOptions& o, std::size_t num_features,
                                std::size_t database_size, double convert_ms, double feature_ms) {
  KeyframeStatus s;
  s.header = header;
  s.id = r.query_id;
  s.status = static_cast<std::uint8_t>(r.status);
  s.status_text = bowg::toString(r.status);
  s.odometry_input = bowg::toString(r.odometry_input);
  s.num_features = static_cast<std::uint32_t>(num_features);
  s.database_size = static_cast<std::uint32_t>(database_size);
  s.candidates_scored = static_cast<std::uint32_t>(r.candidates_scored);
  s.candidates_gated = static_cast<std::uint32_t>(r.candidates_gated);
  s.candidates_gated_cross_run = static_cast<std::uint32_t>(r.candidates_gated_cross_run);
  s.candidates_gated_heading = static_cast<std::uint32_t>(r.candidates_gated_heading);
  s.query_mission = r.mission;
  s.has_candidate = r.has_candidate;
  if (r.has_candidate) {
    s.best_id = r.best.entry;
    s.best_score = r.best.eta;
    s.best_score_sim = r.best.eta_sim;
    s.best_score_word = r.best.eta_w;
    s.best_score_group = r.best.eta_g;
    s.best_score_distribution = r.best.eta_d;
    s.best_mission = r.best_mission;
    s.best_mission_name = r.best_mission_name;
    s.island_first = r.island_first;
    s.island_last = r.island_last;
  }
  if (r.status == bowg::LoopStatus::kLoopDetected) s.match_id = r.match_id;
  s.inliers = static_cast<std::uint32_t>(std::max(0, r.inliers));
  s.word_normaliser = r.word_normaliser;
  s.group_normaliser = r.group_normaliser;
  s.distribution_normaliser = r.distribution_normaliser;
  s.word_divisor = r.word_divisor;
  s.group_divisor = r.group_divisor;
  s.distribution_divisor = r.distribution_divisor;
  s.convert_ms = convert_ms;
  s.feature_ms = feature_ms;
  s.transform_ms = r.timings.transform_ms;
  s.word_groups_ms = r.timings.word_groups_ms;
  s.query_ms = r.timings.query_ms;
  s.islands_ms = r.timings.islands_ms;
  s.verification_ms = r.timings.verification_ms;
  s.total_ms = r.timings.total_ms + convert_ms + feature_ms;
  s.lambda_1 = o.similarity.lambda_1;
  s.lambda_2 = o.similarity.lambda_2;
  s.w_max = o.temporal_score.w_max;
  s.alpha = o.temporal_score.alpha;
  s.fan_bins = o.distribution.fan_bins;
  s.min_score = o.islands.min_score;
  s.temporal_k = o.temporal_verification.k;
  s.min_inliers = o.geometric.min_inliers;
  s.direct_index_level = o.geometric.direct_index_level;
  s.word_groups = o.word_groups.enabled;
  s.distribution = o.distribution.enabled;
  s.temporal_score = o.temporal_score.enabled;
  s.geometric_verification = o.geometric.enabled;
  s.exhaustive_matching = o.geometric.exhaustive;
  return s;
}

}  // namespace bowg_ros
