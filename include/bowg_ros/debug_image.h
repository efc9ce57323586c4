// The ~debug_image: query and match keyframes side by side with the inlier
// correspondences. ROS-free; the nodelet calls it only
// while somebody subscribes.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "bowg/detection/loop_detector.h"

namespace bowg_ros {

/// A BGR image: `query` on the left, `match` on the right (a grey panel
/// when the match image is not cached), inlier lines between them, and
/// `caption` on top, one line per '\n'-separated part. Both inputs are
/// 8-bit grey; either may be empty.
cv::Mat drawDebugImage(const cv::Mat& query, const cv::Mat& match,
                       const std::vector<bowg::Correspondence>& inliers,
                       const std::string& caption);

}  // namespace bowg_ros
