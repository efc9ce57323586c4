// Converts an incoming image (sensor_msgs/Image of any supported encoding, or
// sensor_msgs/CompressedImage) to the 8-bit grey image the feature extractor
// needs. The one conversion of the project: the nodelet, the offline
// evaluator, the bag evaluator and the vocabulary trainer all read images
// through it, so that a bag gives the same grey images live and offline.
// Needs message headers only (no master): unit-tested as plain functions.
#pragma once

#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace bowg_ros {

/// Thrown for an encoding we do not handle, an image whose layout or type
/// does not match its encoding, or compressed data that does not decode; the
/// message names the problem and the encoding or format.
class BadImage : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// mono8, mono16, bgr8, rgb8, bgra8, rgba8, 8UC1 (as mono8), 16UC1 (as mono16).
bool isSupportedEncoding(const std::string& encoding);

/// The supported encodings as a list for messages: "mono8, mono16, ...".
const std::string& supportedEncodings();

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

/// The grey image of an Image message: its layout is checked
/// (imageLayoutProblem) before its buffer is wrapped, then toMono8. A mono8
/// image shares the message's buffer (no copy): keep the message alive while
/// the result is used, or clone it. Throws BadImage naming the problem.
cv::Mat greyFromImage(const sensor_msgs::Image& msg);

/// The grey image decoded from a CompressedImage (any format cv::imdecode
/// reads: jpeg, png, ...). Throws BadImage when the data does not decode.
cv::Mat greyFromCompressed(const sensor_msgs::CompressedImage& msg);

}  // namespace bowg_ros
