// OpenCV ORB descriptors (rBRIEF, Rublee et al. ICCV 2011) for keypoints found
// by any detector, e.g. the GFTT corners of the pipe setting (paper Sec.
// III-A).
//
// What cv::ORB::compute does with provided keypoints (checked on OpenCV 4.6,
// see feature_orb_descriptor_test.cpp): it does NOT compute an orientation;
// it steers its 31x31 pattern by the keypoint's `angle` field as given (so
// an unset angle of -1 means a -1 degree rotation, and 0 is upright); it
// samples pyramid level `octave` (so single-scale corners need octave 0);
// it ignores `size`; it smooths each level with a 7x7, sigma 2 Gaussian; it
// drops keypoints closer than its edgeThreshold to the border and returns
// the rest grouped by octave, i.e. possibly reordered.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

/// ORB's fixed patch: 31x31, half size 15, also the radius of its
/// intensity-centroid disc.
constexpr int kOrbHalfPatch = 15;
/// Border (level pixels) an upright ORB descriptor needs: the pattern stays
/// within +-15, plus one for rounding the keypoint position.
constexpr int kOrbUprightRadius = kOrbHalfPatch + 1;
/// Border a steered ORB descriptor needs: ceil(15 sqrt 2) = 22 (a rotated
/// pattern point stays within 15 sqrt 2 = 21.2 px, rounded to <= 21, plus
/// one for rounding the keypoint position).
constexpr int kOrbSteeredRadius = 22;

/// Multi-scale parameters of the ORB pyramid the keypoints' octaves refer to.
struct OrbPyramid {
  double scale_factor = 1.2;
  int levels = 1;
};

/// True when a keypoint at level `octave` keeps `radius` level pixels from
/// every border of its pyramid level.
bool insideOrbLevel(const cv::KeyPoint& kp, const cv::Size& image_size, const OrbPyramid& pyramid,
                    int radius);

/// ORB descriptors of `keypoints` (index-aligned with the input), steered by
/// each keypoint's `angle` in degrees (pass 0 for upright descriptors; the
/// angle is used as given, never recomputed). Every keypoint must satisfy
/// insideOrbLevel with kOrbUprightRadius (angle 0) or kOrbSteeredRadius
/// (any other angle) and octave < pyramid.levels (throws
/// std::invalid_argument otherwise).
std::vector<Descriptor> computeOrbDescriptors(const cv::Mat& image,
                                              const std::vector<cv::KeyPoint>& keypoints,
                                              const OrbPyramid& pyramid);

}  // namespace bowg
