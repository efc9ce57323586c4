// Reading one image of an image folder for the offline tools (bowg_evaluate
// --images, the vocabulary trainer). A folder of camera frames may hold a
// file that is empty, cut short by a full disk or not an image at all: the
// tools skip it, count it and say why, instead of stopping the run or using
// a half-decoded frame.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "bowg/features/feature_options.h"

namespace bowg {
namespace eval {

/// The image at `path` as 8-bit grey, or an empty Mat with `*why` saying
/// what is wrong: unreadable or empty file, not an image OpenCV decodes, a
/// JPEG without its end-of-image marker (truncated: libjpeg would fill the
/// rest with grey), or more pixels than options.max_image_pixels.
cv::Mat readGreyImage(const std::string& path, const FeatureOptions& options, std::string* why);

}  // namespace eval
}  // namespace bowg
