// Plain BRIEF descriptors computed the way VINS-Mono / VINS-Fusion compute
// them with DVision::BRIEF, so that they index the brief_k10L6.bin
// vocabulary those systems (and the BoWG authors) trained.
//
// Facts relied on, read from the public code (no code copied):
// - HKUST-Aerial-Robotics/VINS-Fusion, loop_fusion/src/keyframe.cpp:
//   BriefExtractor loads x1, x2, y1, y2 from brief_pattern.yml with
//   cv::FileStorage and hands them to BRIEF::importPairs; keyframes call
//   BRIEF::compute(image, keypoints, descriptors) with the default
//   treat_image = true on the 8-bit grey image, for cv::FAST corners
//   (threshold 20) and for the tracked points, with keypoints built from the
//   pixel position only (no angle, no scale). VINS-Mono's
//   pose_graph/src/keyframe.cpp does the same.
// - loop_fusion/src/ThirdParty/DVision/BRIEF.cpp (and BRIEF.h) in the same
//   repository, BRIEF::compute:
//   * treat_image = true smooths the whole image with
//     cv::GaussianBlur(ksize 9x9, sigma_x = sigma_y = 2, default border)
//     before any test;
//   * test i samples (x, y) = ((int)(kp.x + x1[i]), (int)(kp.y + y1[i])) and
//     ((int)(kp.x + x2[i]), (int)(kp.y + y2[i])): float sum truncated
//     toward zero, no rounding and no interpolation;
//   * bit i is set iff I(x1, y1) < I(x2, y2) (strictly less, first point
//     of the pair on the left);
//   * a test with a point outside the image leaves its bit 0;
//   * bit i is index i of the boost::dynamic_bitset; the vocabulary file
//     stores bitset block 0 (bits 0..63) first, so bit i is bit i % 64 of
//     block i / 64 of bowg::Descriptor with no reordering.
//   DVision never steers the pattern (BRIEF is upright): VINS compatibility
//   needs steering off. Here keypoints whose tests would leave the image are
//   rejected by the caller instead of producing zero bits, so the bits of
//   every kept keypoint equal DVision's.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

/// Smoothing DVision::BRIEF applies with treat_image = true (see above).
cv::Mat smoothForBrief(const cv::Mat& image);

/// Distance (px) a keypoint must keep from every image border so that all
/// tests of `pattern` sample inside the image: max |offset| when upright;
/// ceil of the largest offset norm when steered (a rotated, rounded offset
/// never exceeds it).
int briefPatternRadius(const std::vector<cv::Vec4i>& pattern, bool steered);

/// BRIEF descriptors of `keypoints` on `smoothed` (8-bit single-channel,
/// already passed through smoothForBrief when DVision compatibility is
/// wanted). Test i of `pattern` (at most 256 tests) gives bit i.
/// With `steer` and a keypoint angle >= 0 (degrees), each offset (x, y) is
/// first rotated by the angle, (x cos a - y sin a, x sin a + y cos a), and
/// rounded to the nearest pixel (OpenCV ORB's steering convention); angle
/// 0 gives exactly the upright bits. Throws std::invalid_argument when a
/// test would sample outside the image or the pattern has > 256 tests.
std::vector<Descriptor> computeBriefDescriptors(const cv::Mat& smoothed,
                                                const std::vector<cv::Vec4i>& pattern,
                                                const std::vector<cv::KeyPoint>& keypoints,
                                                bool steer);

}  // namespace bowg
