// FeatureOptions::validate(). Messages start with "features.<field>" (the
// member name in the nodelet's parameter namespace), like options.cpp, and
// comparisons are written so that NaN fails them.
#include <cmath>
#include <sstream>
#include <string>

#include "bowg/errors.h"
#include "bowg/feature_extractor.h"

namespace bowg {
namespace {

// FAST compares 8-bit intensity differences: thresholds >= 255 find nothing.
const int kMaxFastThreshold = 254;

template <typename T>
std::string str(T v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

[[noreturn]] void fail(const std::string& field, const std::string& why, const std::string& got) {
  throw InvalidParameter("features." + field + " " + why + " (got " + got + ")");
}

void requireIntAtLeast(const std::string& field, int v, int lo) {
  if (v < lo) fail(field, "must be >= " + str(lo), str(v));
}

}  // namespace

void FeatureOptions::validate() const {
  if (detector != Detector::kGftt && detector != Detector::kOrb) {
    fail("detector", "must be gftt or orb", str(static_cast<int>(detector)));
  }
  if (descriptor != DescriptorType::kOrb && descriptor != DescriptorType::kBrief) {
    fail("descriptor", "must be orb or brief", str(static_cast<int>(descriptor)));
  }
  requireIntAtLeast("gftt_max_corners", gftt_max_corners, 1);
  // cv::goodFeaturesToTrack asserts quality > 0; above 1 nothing passes.
  if (!(gftt_quality_level > 0.0 && gftt_quality_level <= 1.0)) {
    fail("gftt_quality_level", "must be in (0, 1]", str(gftt_quality_level));
  }
  if (!std::isfinite(gftt_min_distance) || !(gftt_min_distance >= 0.0)) {
    fail("gftt_min_distance", "must be a finite number >= 0", str(gftt_min_distance));
  }
  requireIntAtLeast("gftt_block_size", gftt_block_size, 1);
  if (!std::isfinite(gftt_keypoint_size) || !(gftt_keypoint_size > 0.0)) {
    fail("gftt_keypoint_size", "must be a finite number > 0", str(gftt_keypoint_size));
  }
  requireIntAtLeast("orb_max_features", orb_max_features, 1);
  // cv::ORB needs scale_factor > 1 to build a shrinking pyramid.
  if (!std::isfinite(orb_scale_factor) || !(orb_scale_factor > 1.0)) {
    fail("orb_scale_factor", "must be a finite number > 1", str(orb_scale_factor));
  }
  requireIntAtLeast("orb_levels", orb_levels, 1);
  if (orb_fast_threshold < 1 || orb_fast_threshold > kMaxFastThreshold) {
    fail("orb_fast_threshold", "must be in [1, " + str(kMaxFastThreshold) + "]",
         str(orb_fast_threshold));
  }
  if (descriptor == DescriptorType::kBrief && brief_pattern_path.empty()) {
    fail("brief_pattern_path", "must name a pattern file when features.descriptor is brief",
         "an empty path");
  }
}

}  // namespace bowg
