#include "bowg/features/orientation.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace bowg {

float intensityCentroidAngle(const cv::Mat& image, cv::Point2f pt, int radius) {
  if (image.type() != CV_8UC1) {
    throw std::invalid_argument("intensityCentroidAngle: image must be 8-bit single-channel");
  }
  if (radius < 1) throw std::invalid_argument("intensityCentroidAngle: radius must be >= 1");
  const int cx = cvRound(pt.x);
  const int cy = cvRound(pt.y);
  if (cx - radius < 0 || cy - radius < 0 || cx + radius >= image.cols ||
      cy + radius >= image.rows) {
    throw std::invalid_argument("intensityCentroidAngle: disc of radius " + std::to_string(radius) +
                                " around (" + std::to_string(cx) + ", " + std::to_string(cy) +
                                ") leaves the " + std::to_string(image.cols) + "x" +
                                std::to_string(image.rows) + " image");
  }
  // r (r + 1) = (r + 1/2)^2 - 1/4: the integer disc of radius r + 1/2, which
  // keeps the rim pixels that ORB's circular patch also keeps.
  const int r2 = radius * (radius + 1);
  long long m10 = 0;
  long long m01 = 0;
  for (int v = -radius; v <= radius; ++v) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(cy + v);
    long long row_sum = 0;
    for (int u = -radius; u <= radius; ++u) {
      if (u * u + v * v > r2) continue;
      const int value = row[cx + u];
      m10 += static_cast<long long>(u) * value;
      row_sum += value;
    }
    m01 += static_cast<long long>(v) * row_sum;
  }
  if (m10 == 0 && m01 == 0) return 0.f;
  double deg = std::atan2(static_cast<double>(m01), static_cast<double>(m10)) * 180.0 / M_PI;
  if (deg < 0.0) deg += 360.0;
  const float out = static_cast<float>(deg);
  return out >= 360.f ? 0.f : out;  // 359.99999999 rounds up to 360 in float
}

}  // namespace bowg
