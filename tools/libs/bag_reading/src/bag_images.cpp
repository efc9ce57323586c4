// Images of a rosbag (see bag_images.h).
#include "bowg_bag_reading/bag_images.h"

#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include "bowg/core/errors.h"
#include "bowg_ros/image_conversion.h"

namespace bowg {
namespace bag {
namespace {

[[noreturn]] void notAnImage(const rosbag::MessageInstance& m, const std::string& bag_path) {
  throw FormatError("bag '" + bag_path + "', topic " + m.getTopic() + " holds " + m.getDataType() +
                    ", not sensor_msgs/Image or sensor_msgs/CompressedImage");
}

}  // namespace

BagImage readBagImage(const rosbag::MessageInstance& m, const std::string& bag_path,
                      const FeatureOptions& options) {
  BagImage out;
  try {
    if (const sensor_msgs::Image::ConstPtr img = m.instantiate<sensor_msgs::Image>()) {
      out.stamp = img->header.stamp;
      // Cloned: the message dies with this scope.
      out.grey = bowg_ros::greyFromImage(*img, options).clone();
      return out;
    }
    if (const sensor_msgs::CompressedImage::ConstPtr c =
            m.instantiate<sensor_msgs::CompressedImage>()) {
      out.stamp = c->header.stamp;
      out.grey = bowg_ros::greyFromCompressed(*c, options);
      return out;
    }
  } catch (const BadImage& e) {
    out.grey = cv::Mat();
    out.check = imageRefusal(e.problem(), "bag '" + bag_path + "', topic " + m.getTopic() + " at " +
                                              std::to_string(m.getTime().toSec()) + ": " +
                                              e.check().detail);
    return out;
  }
  notAnImage(m, bag_path);
}

ros::Time bagImageStamp(const rosbag::MessageInstance& m, const std::string& bag_path) {
  if (const sensor_msgs::Image::ConstPtr img = m.instantiate<sensor_msgs::Image>()) {
    return img->header.stamp;
  }
  if (const sensor_msgs::CompressedImage::ConstPtr c =
          m.instantiate<sensor_msgs::CompressedImage>()) {
    return c->header.stamp;
  }
  notAnImage(m, bag_path);
}

}  // namespace bag
}  // namespace bowg
