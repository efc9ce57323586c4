// Deterministic synthetic test images for the feature tests, drawn with
// OpenCV (no data files needed).
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace bowg {
namespace test {

/// Grey background with `blobs` random filled ellipses and rectangles of
/// random intensity, lightly blurred: plenty of corners at many scales.
inline cv::Mat texturedImage(int width, int height, int blobs, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat img(height, width, CV_8UC1, cv::Scalar(96));
  for (int i = 0; i < blobs; ++i) {
    const cv::Point c(rng.uniform(0, width), rng.uniform(0, height));
    const int value = rng.uniform(0, 256);
    if (rng.uniform(0, 2) == 0) {
      const cv::Size axes(rng.uniform(3, 25), rng.uniform(3, 25));
      cv::ellipse(img, c, axes, rng.uniform(0.0, 180.0), 0, 360, cv::Scalar(value), cv::FILLED);
    } else {
      const cv::Point d(rng.uniform(4, 30), rng.uniform(4, 30));
      cv::rectangle(img, c, c + d, cv::Scalar(value), cv::FILLED);
    }
  }
  cv::GaussianBlur(img, img, cv::Size(3, 3), 0.8);
  return img;
}

/// Black/white checkerboard with `square` px squares.
inline cv::Mat checkerboard(int width, int height, int square) {
  cv::Mat img(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      img.at<std::uint8_t>(y, x) = ((x / square + y / square) % 2) ? 255 : 0;
    }
  }
  return img;
}

}  // namespace test
}  // namespace bowg
