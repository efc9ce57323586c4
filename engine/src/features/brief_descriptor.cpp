#include "bowg/features/brief_descriptor.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace bowg {
namespace {

// DVision::BRIEF's smoothing (brief_descriptor.h).
const int kSmoothKernel = 9;
const double kSmoothSigma = 2.0;

int sampleAt(const cv::Mat& image, float kx, float ky, int dx, int dy) {
  // DVision: (int)(kp.pt.x + offset), a float sum truncated toward zero.
  const int x = static_cast<int>(kx + static_cast<float>(dx));
  const int y = static_cast<int>(ky + static_cast<float>(dy));
  // Also rejects sums in (-1, 0), which truncate to 0 but lie outside.
  if (kx + static_cast<float>(dx) < 0.f || ky + static_cast<float>(dy) < 0.f || x >= image.cols ||
      y >= image.rows) {
    throw std::invalid_argument(
        "BRIEF test at (" + std::to_string(kx + dx) + ", " + std::to_string(ky + dy) +
        ") leaves the " + std::to_string(image.cols) + "x" + std::to_string(image.rows) + " image");
  }
  return image.ptr<std::uint8_t>(y)[x];
}

}  // namespace

cv::Mat smoothForBrief(const cv::Mat& image) {
  cv::Mat out;
  cv::GaussianBlur(image, out, cv::Size(kSmoothKernel, kSmoothKernel), kSmoothSigma, kSmoothSigma);
  return out;
}

int briefPatternRadius(const std::vector<cv::Vec4i>& pattern, bool steered) {
  double r = 0.0;
  for (const cv::Vec4i& p : pattern) {
    if (steered) {
      r = std::max(r, std::max(std::hypot(p[0], p[1]), std::hypot(p[2], p[3])));
    } else {
      r = std::max({r, double(std::abs(p[0])), double(std::abs(p[1])), double(std::abs(p[2])),
                    double(std::abs(p[3]))});
    }
  }
  return static_cast<int>(std::ceil(r));
}

std::vector<Descriptor> computeBriefDescriptors(const cv::Mat& smoothed,
                                                const std::vector<cv::Vec4i>& pattern,
                                                const std::vector<cv::KeyPoint>& keypoints,
                                                bool steer) {
  if (smoothed.type() != CV_8UC1) {
    throw std::invalid_argument("computeBriefDescriptors: image must be 8-bit single-channel");
  }
  if (pattern.size() > 256) {
    throw std::invalid_argument("computeBriefDescriptors: pattern has " +
                                std::to_string(pattern.size()) + " tests, at most 256 fit");
  }
  std::vector<Descriptor> out(keypoints.size());
  std::vector<cv::Vec4i> rotated(pattern.size());
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    const std::vector<cv::Vec4i>* tests = &pattern;
    if (steer && kp.angle >= 0.f) {
      const double a = kp.angle * M_PI / 180.0;
      const double c = std::cos(a);
      const double s = std::sin(a);
      for (std::size_t i = 0; i < pattern.size(); ++i) {
        const cv::Vec4i& p = pattern[i];
        rotated[i] = cv::Vec4i(cvRound(c * p[0] - s * p[1]), cvRound(s * p[0] + c * p[1]),
                               cvRound(c * p[2] - s * p[3]), cvRound(s * p[2] + c * p[3]));
      }
      tests = &rotated;
    }
    Descriptor& d = out[k];
    for (std::size_t i = 0; i < tests->size(); ++i) {
      const cv::Vec4i& p = (*tests)[i];
      const int a = sampleAt(smoothed, kp.pt.x, kp.pt.y, p[0], p[1]);
      const int b = sampleAt(smoothed, kp.pt.x, kp.pt.y, p[2], p[3]);
      if (a < b) d.bits[i / 64] |= std::uint64_t{1} << (i % 64);
    }
  }
  return out;
}

}  // namespace bowg
