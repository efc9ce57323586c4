// Upstream features -> ImageFeatures (see feature_arrays.h).
#include "bowg/features/feature_arrays.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "bowg/features/descriptor_conversion.h"

namespace bowg {
namespace {

[[noreturn]] void refuse(const std::string& what) {
  throw std::invalid_argument("KeyframeFeatures: " + what);
}

void checkLayout(const FeatureArrays& a, const FeatureOptions& options) {
  const std::size_t n = a.x.size();
  if (a.y.size() != n || a.size.size() != n || a.angle.size() != n || a.response.size() != n ||
      a.octave.size() != n) {
    refuse("x, y, size, angle, response and octave must have the same length (x has " +
           std::to_string(n) + ")");
  }
  if (a.descriptors.size() / kDescriptorBytes != n ||
      a.descriptors.size() % kDescriptorBytes != 0) {
    refuse("descriptors has " + std::to_string(a.descriptors.size()) + " bytes, expected " +
           std::to_string(n) + " x " + std::to_string(kDescriptorBytes));
  }
  if (a.image_width == 0 || a.image_height == 0) {
    refuse("image_width and image_height must be > 0");
  }
  const std::string size = imageSizeProblem(a.image_width, a.image_height, options);
  if (!size.empty()) refuse("image size " + size);
}

// Later stages (word groups, RANSAC, the database's packed positions)
// compute with these values: a NaN, an infinity or a position far outside
// the image would poison them.
void checkKeypoint(const Keypoint& k, std::size_t i, const FeatureArrays& a) {
  if (!std::isfinite(k.x) || !std::isfinite(k.y)) {
    refuse("keypoint " + std::to_string(i) + " has a non-finite position");
  }
  if (k.x < 0.f || k.y < 0.f || k.x > static_cast<float>(a.image_width) ||
      k.y > static_cast<float>(a.image_height)) {
    refuse("keypoint " + std::to_string(i) + " at (" + std::to_string(k.x) + ", " +
           std::to_string(k.y) + ") lies outside the " + std::to_string(a.image_width) + " x " +
           std::to_string(a.image_height) + " image");
  }
  if (!std::isfinite(k.size) || k.size < 0.f) {
    refuse("keypoint " + std::to_string(i) + " has a size that is negative or not finite");
  }
  if (!std::isfinite(k.angle) || !std::isfinite(k.response)) {
    refuse("keypoint " + std::to_string(i) + " has a non-finite angle or response");
  }
}

}  // namespace

ImageFeatures featuresFromArrays(const FeatureArrays& a, const FeatureOptions& options) {
  checkLayout(a, options);
  const std::size_t n = a.x.size();
  ImageFeatures f;
  f.image_width = static_cast<int>(a.image_width);
  f.image_height = static_cast<int>(a.image_height);
  f.keypoints.resize(n);
  f.descriptors.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Keypoint& k = f.keypoints[i];
    k.x = a.x[i];
    k.y = a.y[i];
    k.size = a.size[i];
    k.angle = a.angle[i];
    k.response = a.response[i];
    k.octave = a.octave[i];
    checkKeypoint(k, i, a);
    f.descriptors[i] = descriptorFromBytes(&a.descriptors[i * kDescriptorBytes]);
  }
  return f;
}

}  // namespace bowg
