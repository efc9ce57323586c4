// Feature extraction (paper Sec. III-A; the pipe experiments use GFTT, the
// public datasets multi-scale ORB/FAST). Produces 256-bit binary descriptors
// and keeps the keypoint size, which is the word-group radius.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "bowg/core/types.h"
#include "bowg/features/feature_options.h"

namespace bowg {

class FeatureExtractor {
 public:
  /// Validates options, loads pattern and mask files (throws IoError /
  /// FormatError with the path on failure).
  explicit FeatureExtractor(const FeatureOptions& options);

  /// `image` must be 8-bit single-channel and non-empty (throws
  /// std::invalid_argument otherwise). Keypoints whose descriptor patch
  /// would leave the image are dropped.
  ImageFeatures extract(const cv::Mat& image) const;

  const FeatureOptions& options() const { return options_; }

 private:
  FeatureOptions options_;
  cv::Mat mask_;
  std::vector<cv::Vec4i> brief_pattern_;  // (x1, y1, x2, y2) per bit
};

}  // namespace bowg
