// All conversions between bowg engine types and ROS messages, in one place
// (docs/style-examples.md, habit 2). No ROS node handles here: pure functions,
// unit-tested without a master.
#pragma once

#include <nav_msgs/Odometry.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Header.h>

#include "bowg/core/types.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/features/feature_options.h"
#include "bowg_ros/KeyframeFeatures.h"
#include "bowg_ros/KeyframeStatus.h"
#include "bowg_ros/LoopClosure.h"
#include "bowg_ros/odometry_reading.h"

namespace bowg_ros {

/// The position reading of an odometry message: its position, and its
/// heading (bowg::headingFromQuaternion of the orientation; unknown when
/// the orientation is not a unit quaternion, as the all-zero one of a
/// driver without orientation).
OdometryReading toReading(const nav_msgs::Odometry& msg);

/// fx, fy, cx, cy from K; invalid (valid == false) when K is all zero or
/// fx/fy are not positive, as for an uncalibrated camera_info.
bowg::CameraIntrinsics toIntrinsics(const sensor_msgs::CameraInfo& info);

/// Checked by bowg::featuresFromArrays: throws std::invalid_argument when
/// the arrays differ in length, the descriptor block is not N x 32 bytes,
/// the image size is zero or over options.max_image_pixels, or a keypoint
/// holds a non-finite value or a negative size.
bowg::ImageFeatures fromMessage(const KeyframeFeatures& msg,
                                const bowg::FeatureOptions& options = bowg::FeatureOptions());
KeyframeFeatures toMessage(const bowg::ImageFeatures& features, const std_msgs::Header& header);

/// The covariance of LoopClosure.relative_pose (6x6 row-major, x y z rx ry rz):
/// the translation block is `translation_covariance` (3x3 row-major, m^2)
/// when the odometry gave the scale, else UNOBSERVABLE_SCALE_VARIANCE on its
/// diagonal (two views do not fix the scale); rotation variance sigma^2 with
/// sigma = 0.05 rad * sqrt(15 / inliers), a heuristic that shrinks as
/// 1/sqrt(n) with the RANSAC inlier count. Without a pose every diagonal
/// entry is UNOBSERVABLE_SCALE_VARIANCE.
void fillRelativePoseCovariance(bool has_pose, int inliers, const double* translation_covariance,
                                double* covariance36);
/// The same without a measured translation (scale unknown).
inline void fillRelativePoseCovariance(bool has_pose, int inliers, double* covariance36) {
  fillRelativePoseCovariance(has_pose, inliers, nullptr, covariance36);
}

/// A LoopClosure from a result with status kLoopDetected. `header` is the
/// query image's header (its frame_id the query camera's optical frame).
LoopClosure toLoopClosure(const bowg::LoopResult& result, const std_msgs::Header& header,
                          bool with_correspondences);

/// One KeyframeStatus per processed keyframe; `options` are the options the
/// detector used, `feature_ms`/`convert_ms` the nodelet's own stages.
KeyframeStatus toKeyframeStatus(const bowg::LoopResult& result, const std_msgs::Header& header,
                                const bowg::LoopDetectorOptions& options, std::size_t num_features,
                                std::size_t database_size, double convert_ms, double feature_ms);

}  // namespace bowg_ros
