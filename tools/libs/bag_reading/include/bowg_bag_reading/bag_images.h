// Images read from a rosbag (sensor_msgs/Image or sensor_msgs/CompressedImage
// on one topic), converted exactly as the nodelet converts its input
// (bowg_ros/image_conversion.h). Used by the offline evaluator, the bag evaluator and
// the vocabulary trainer.
#pragma once

#include <ros/time.h>
#include <rosbag/message_instance.h>

#include <opencv2/core.hpp>
#include <string>

#include "bowg/features/feature_options.h"
#include "bowg/features/image_check.h"

namespace bowg {
namespace bag {

/// One image of a bag: its grey image (owned: independent of the message)
/// and its header stamp; a refused image has an empty grey image and its
/// reason in `check` (the same classification as the nodelet's).
struct BagImage {
  cv::Mat grey;
  ros::Time stamp;
  ImageCheck check;
};

/// Throws bowg::FormatError naming the bag and the topic when the message is
/// neither an Image nor a CompressedImage. A bad image (empty, truncated,
/// too large for `options`, ...) does not throw: its `check` says why, its
/// detail naming the bag, topic and time, so that one bad frame skips that
/// frame and not the run.
BagImage readBagImage(const rosbag::MessageInstance& message, const std::string& bag_path,
                      const FeatureOptions& options);

/// The header stamp only (no decoding); same errors for other message types.
ros::Time bagImageStamp(const rosbag::MessageInstance& message, const std::string& bag_path);

}  // namespace bag
}  // namespace bowg
