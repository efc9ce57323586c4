// Options of the feature stage (paper Sec. III-A): detector, descriptor and
// their parameters; validate() throws InvalidParameter naming the field as
// "features.<field>".
#pragma once

#include <string>

namespace bowg {

struct FeatureOptions {
  enum class Detector { kGftt, kOrb };
  enum class DescriptorType { kOrb, kBrief };

  Detector detector = Detector::kGftt;
  DescriptorType descriptor = DescriptorType::kOrb;

  // GFTT (Shi-Tomasi) corners.
  int gftt_max_corners = 500;
  double gftt_quality_level = 0.01;
  double gftt_min_distance = 10.0;  ///< px
  int gftt_block_size = 3;          ///< px
  bool gftt_use_harris = false;
  /// Keypoint size given to GFTT corners (px). GFTT has no scale; this is
  /// the word-group radius. (Descriptor patches are fixed: ORB's 31x31,
  /// BRIEF's pattern extent.)
  double gftt_keypoint_size = 31.0;
  /// Pyramid levels GFTT corners are found on (scale orb_scale_factor, as
  /// ORB's): 1 = the image alone. A revisit a few cm off the earlier pass
  /// sees the near wall at another scale; corners of a coarser level keep
  /// their descriptors there. Needs the ORB descriptor (BRIEF samples level
  /// 0 only).
  int gftt_levels = 1;

  // Multi-scale ORB/FAST.
  int orb_max_features = 500;
  double orb_scale_factor = 1.2;
  int orb_levels = 8;
  int orb_fast_threshold = 20;

  /// rBRIEF: steer the descriptor by the intensity-centroid orientation
  /// (pipe robots roll). Off = unoriented (upright) descriptors.
  bool compute_orientation = true;
  /// Plain BRIEF: path of a pattern file in the layout of VINS'
  /// brief_pattern.yml (256 pairs x1 y1 x2 y2), needed for brief_k10L6.bin.
  std::string brief_pattern_path;
  /// Optional 8-bit mask image (non-zero = usable), e.g. to blank burned-in
  /// text overlays; must match the image size.
  std::string mask_path;
  /// Largest image accepted, in pixels (width x height; default 4096 x
  /// 4096). A camera frame is far smaller; a larger one (a wrong topic, a
  /// corrupt header) would take gigabytes and seconds. The nodelet drops and
  /// counts such frames, the tools skip them with a warning.
  int max_image_pixels = 4096 * 4096;

  void validate() const;  ///< throws InvalidParameter naming the field
};

/// "" when an image of width x height is within options.max_image_pixels,
/// else what is wrong ("1000 x 1000 = 1000000 pixels, more than
/// max_image_pixels 16777216").
std::string imageSizeProblem(long long width, long long height, const FeatureOptions& options);

}  // namespace bowg
