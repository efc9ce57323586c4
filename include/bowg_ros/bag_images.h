// Images read from a rosbag (sensor_msgs/Image or sensor_msgs/CompressedImage
// on one topic), converted exactly as the nodelet converts its input
// (image_conversion.h). Used by the offline evaluator, the bag evaluator and
// the vocabulary trainer.
#pragma once

#include <ros/time.h>
#include <rosbag/message_instance.h>

#include <opencv2/core.hpp>
#include <string>

namespace bowg_ros {

/// One image of a bag: its grey image (owned: independent of the message)
/// and its header stamp.
struct BagImage {
  cv::Mat grey;
  ros::Time stamp;
};

/// Throws bowg::FormatError naming the bag and the topic when the message is
/// neither an Image nor a CompressedImage, or cannot be converted.
BagImage readBagImage(const rosbag::MessageInstance& message, const std::string& bag_path);

/// The header stamp only (no decoding); same errors for other message types.
ros::Time bagImageStamp(const rosbag::MessageInstance& message, const std::string& bag_path);

}  // namespace bowg_ros
