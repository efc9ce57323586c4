// Converts an incoming image of any supported sensor_msgs encoding to the
// 8-bit grey image the feature extractor needs. ROS-free (encodings are the
// sensor_msgs/image_encodings strings), so it is unit-tested without a master.
#pragma once

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace bowg_ros {

/// Thrown for an encoding we do not handle, or an image whose type does not
/// match its encoding; the message names the encoding.
class UnsupportedEncoding : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// mono8, mono16, bgr8, rgb8, bgra8, rgba8.
bool isSupportedEncoding(const std::string& encoding);

/// Why an image message's layout cannot be read safely ("" when it can):
/// an unsupported encoding, a zero width or height, a step shorter than a
/// row, or less data than height x step (a reader would run past the
/// buffer). Checked before the message's buffer is wrapped.
std::string imageLayoutProblem(std::uint32_t width, std::uint32_t height, std::uint32_t step,
                               std::size_t data_size, const std::string& encoding);

/// The grey image. mono8 is returned as is (shares the data: no copy);
/// mono16 is scaled by 1/256 (the high byte; the full 16-bit range maps to
/// 0..255); colour images use OpenCV's luma weights.
cv::Mat toMono8(const cv::Mat& image, const std::string& encoding);

}  // namespace bowg_ros
