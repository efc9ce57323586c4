// Features computed upstream (the nodelet's keyframe_features input, e.g. a
// VIO front end's corners) in the layout of the KeyframeFeatures message:
// parallel arrays and N x 32 descriptor bytes. The checked conversion to
// ImageFeatures is ROS-free, so that it is unit-tested and fuzzed without
// message headers; the ROS layer only copies the message's fields in.
#pragma once

#include <cstdint>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/features/feature_options.h"

namespace bowg {

struct FeatureArrays {
  std::uint32_t image_width = 0;
  std::uint32_t image_height = 0;
  std::vector<float> x, y, size, angle, response;
  std::vector<std::int32_t> octave;
  std::vector<std::uint8_t> descriptors;  ///< N rows of kDescriptorBytes
};

/// The features, or std::invalid_argument naming the field: arrays of
/// different lengths, a descriptor block that is not N x 32 bytes, a zero
/// image size or one over options.max_image_pixels, a position outside the
/// image, a position, size, angle or response that is not a finite number,
/// a negative size.
ImageFeatures featuresFromArrays(const FeatureArrays& arrays, const FeatureOptions& options);

}  // namespace bowg
