#include "bowg/features/orb_descriptor.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "bowg/features/descriptor_conversion.h"

namespace bowg {

bool insideOrbLevel(const cv::KeyPoint& kp, const cv::Size& image_size, const OrbPyramid& pyramid,
                    int radius) {
  const double scale = std::pow(pyramid.scale_factor, kp.octave);
  // OpenCV sizes level i as cvRound(size / scale_factor^i).
  const int w = cvRound(image_size.width / scale);
  const int h = cvRound(image_size.height / scale);
  const double x = kp.pt.x / scale;
  const double y = kp.pt.y / scale;
  return x >= radius && y >= radius && x <= w - 1 - radius && y <= h - 1 - radius;
}

std::vector<Descriptor> computeOrbDescriptors(const cv::Mat& image,
                                              const std::vector<cv::KeyPoint>& keypoints,
                                              const OrbPyramid& pyramid) {
  std::vector<cv::KeyPoint> work(keypoints);
  for (std::size_t i = 0; i < work.size(); ++i) {
    const cv::KeyPoint& kp = work[i];
    // An upright pattern (angle 0) needs less border than a steered one.
    const int radius = kp.angle == 0.f ? kOrbUprightRadius : kOrbSteeredRadius;
    if (kp.octave < 0 || kp.octave >= pyramid.levels ||
        !insideOrbLevel(kp, image.size(), pyramid, radius)) {
      throw std::invalid_argument("computeOrbDescriptors: keypoint " + std::to_string(i) + " at (" +
                                  std::to_string(kp.pt.x) + ", " + std::to_string(kp.pt.y) +
                                  "), octave " + std::to_string(kp.octave) +
                                  " is too close to the border or outside the pyramid");
    }
    // ORB reorders its output by octave: remember where each came from.
    work[i].class_id = static_cast<int>(i);
  }
  std::vector<Descriptor> out(keypoints.size());
  if (work.empty()) return out;
  // edgeThreshold only filters provided keypoints here (the pyramid border is
  // at least the rotated patch size whatever it is); the check above is
  // stricter, so ORB drops nothing.
  cv::Ptr<cv::ORB> orb = cv::ORB::create(
      static_cast<int>(work.size()), static_cast<float>(pyramid.scale_factor), pyramid.levels,
      kOrbUprightRadius, 0, 2, cv::ORB::HARRIS_SCORE, 2 * kOrbHalfPatch + 1);
  cv::Mat mat;
  orb->compute(image, work, mat);
  if (static_cast<int>(work.size()) != mat.rows || work.size() != keypoints.size()) {
    throw std::logic_error("computeOrbDescriptors: cv::ORB dropped " +
                           std::to_string(keypoints.size() - work.size()) +
                           " keypoints that passed the border check");
  }
  const std::vector<Descriptor> computed = descriptorsFromMat(mat);
  for (std::size_t j = 0; j < work.size(); ++j) {
    out[static_cast<std::size_t>(work[j].class_id)] = computed[j];
  }
  return out;
}

}  // namespace bowg
