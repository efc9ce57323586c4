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
#include <string>

#include "bowg/features/feature_options.h"
#include "bowg/features/image_check.h"

namespace bowg_ros {

/// Thrown for a refused image: carries the reason (bowg::ImageProblem) of
/// the one classification of bad images (bowg/features/image_check.h).
using BadImage = bowg::BadImage;

/// mono8, mono16, bgr8, rgb8, bgra8, rgba8, 8UC1 (as mono8), 16UC1 (as mono16).
bool isSupportedEncoding(const std::string& encoding);

/// The supported encodings as a list for messages: "mono8, mono16, ...".
const std::string& supportedEncodings();

/// Whether an image message's layout can be read safely: an unsupported
/// encoding is unsupported_format; a zero width or height bad_header; a step
/// shorter than a row, a step that is not a whole number of channel values
/// (mono16 with an odd step) or less data than height x step malformed.
/// Checked before the message's buffer is wrapped.
bowg::ImageCheck checkImageLayout(std::uint32_t width, std::uint32_t height, std::uint32_t step,
                                  std::size_t data_size, const std::string& encoding);

/// The layout, then width x height against options.max_image_pixels
/// (too_large): all an Image message is checked for before conversion.
bowg::ImageCheck checkImage(const sensor_msgs::Image& msg, const bowg::FeatureOptions& options);

/// The header check of a CompressedImage (bowg::checkEncodedImage: empty,
/// unsupported format, bad header, truncated, too large), with nothing
/// decoded; the refusal's detail names the message's format field.
bowg::ImageCheck checkCompressed(const sensor_msgs::CompressedImage& msg,
                                 const bowg::FeatureOptions& options);

/// The grey image. mono8 is returned as is (shares the data: no copy);
/// mono16 is scaled by 1/256 (the high byte; the full 16-bit range maps to
/// 0..255); colour images use OpenCV's luma weights.
cv::Mat toMono8(const cv::Mat& image, const std::string& encoding);

/// The grey image of an Image message: checked (checkImage) before its
/// buffer is wrapped, then toMono8. A mono8 image shares the message's
/// buffer (no copy): keep the message alive while the result is used, or
/// clone it. Throws BadImage with the reason.
cv::Mat greyFromImage(const sensor_msgs::Image& msg,
                      const bowg::FeatureOptions& options = bowg::FeatureOptions());

/// The grey image decoded from a CompressedImage (PNG, JPEG, BMP, binary
/// PNM: bowg/features/image_header.h), checked from its header before it is
/// decoded (bowg::decodeGreyImage). Throws BadImage with the reason.
cv::Mat greyFromCompressed(const sensor_msgs::CompressedImage& msg,
                           const bowg::FeatureOptions& options = bowg::FeatureOptions());

}  // namespace bowg_ros
