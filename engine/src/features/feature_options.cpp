// FeatureOptions::validate(). Messages start with "features.<field>" (the
// member name in the nodelet's parameter namespace), as every stage's
// (core/validation.h).
#include "bowg/features/feature_options.h"

#include <cmath>

#include "bowg/core/validation.h"

namespace bowg {
namespace {

// FAST compares 8-bit intensity differences: thresholds >= 255 find nothing.
const int kMaxFastThreshold = 254;

}  // namespace

using namespace check;

void FeatureOptions::validate() const {
  if (detector != Detector::kGftt && detector != Detector::kOrb) {
    fail("features.detector", "must be gftt or orb", str(static_cast<int>(detector)));
  }
  if (descriptor != DescriptorType::kOrb && descriptor != DescriptorType::kBrief) {
    fail("features.descriptor", "must be orb or brief", str(static_cast<int>(descriptor)));
  }
  requireIntAtLeast("features.gftt_max_corners", gftt_max_corners, 1);
  // cv::goodFeaturesToTrack asserts quality > 0; above 1 nothing passes.
  if (!(gftt_quality_level > 0.0 && gftt_quality_level <= 1.0)) {
    fail("features.gftt_quality_level", "must be in (0, 1]", str(gftt_quality_level));
  }
  requireFiniteAtLeast("features.gftt_min_distance", gftt_min_distance, 0.0);
  requireIntAtLeast("features.gftt_block_size", gftt_block_size, 1);
  requireFinitePositive("features.gftt_keypoint_size", gftt_keypoint_size);
  requireIntInRange("features.gftt_levels", gftt_levels, 1, 32);
  if (gftt_levels > 1 && descriptor == DescriptorType::kBrief) {
    fail("features.gftt_levels", "must be 1 with the brief descriptor (it samples level 0 only)",
         str(gftt_levels));
  }
  requireIntAtLeast("features.orb_max_features", orb_max_features, 1);
  // cv::ORB needs scale_factor > 1 to build a shrinking pyramid.
  if (!std::isfinite(orb_scale_factor) || !(orb_scale_factor > 1.0)) {
    fail("features.orb_scale_factor", "must be a finite number > 1", str(orb_scale_factor));
  }
  requireIntAtLeast("features.orb_levels", orb_levels, 1);
  requireIntInRange("features.orb_fast_threshold", orb_fast_threshold, 1, kMaxFastThreshold);
  requireIntAtLeast("features.max_image_pixels", max_image_pixels, 1);
  if (descriptor == DescriptorType::kBrief && brief_pattern_path.empty()) {
    fail("features.brief_pattern_path",
         "must name a pattern file when features.descriptor is brief", "an empty path");
  }
}

std::string imageSizeProblem(long long width, long long height, const FeatureOptions& options) {
  // Header fields reach 2^32 each: divide rather than multiply to compare.
  if (width <= 0 || height <= 0 || width <= options.max_image_pixels / height) return "";
  const unsigned long long pixels =
      static_cast<unsigned long long>(width) * static_cast<unsigned long long>(height);
  return std::to_string(width) + " x " + std::to_string(height) + " = " + std::to_string(pixels) +
         " pixels, more than max_image_pixels " + std::to_string(options.max_image_pixels);
}

}  // namespace bowg
