#include "bowg/features/orientation.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace bowg {
namespace {

// The sum and the first moment sum_u u * I(u) of row[-w..w]. Acc: int where
// the sums fit in it (vectorises), long long otherwise.
template <typename Acc>
void rowMoments(const std::uint8_t* row, int w, long long* sum, long long* moment) {
  Acc s = 0, m = 0;
  for (int u = -w; u <= w; ++u) {
    const Acc value = row[u];
    m += static_cast<Acc>(u) * value;
    s += value;
  }
  *sum = s;
  *moment = m;
}

}  // namespace

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
    // The row's half-width in the disc: the largest u with u^2 <= r2 - v^2
    // (integer exact), so that the row is one run without a test per pixel.
    const int limit = r2 - v * v;
    int w = static_cast<int>(std::sqrt(static_cast<double>(limit)));
    while ((w + 1) * (w + 1) <= limit) ++w;
    while (w * w > limit) --w;
    const std::uint8_t* row = image.ptr<std::uint8_t>(cy + v) + cx;
    long long row_sum = 0;
    long long row_moment = 0;
    // With |u| <= 1000 a row's moment is below 255 * 1000 * 1001 < 2^31.
    if (w <= 1000) {
      rowMoments<int>(row, w, &row_sum, &row_moment);
    } else {
      rowMoments<long long>(row, w, &row_sum, &row_moment);
    }
    m10 += row_moment;
    m01 += static_cast<long long>(v) * row_sum;
  }
  if (m10 == 0 && m01 == 0) return 0.f;
  double deg = std::atan2(static_cast<double>(m01), static_cast<double>(m10)) * 180.0 / M_PI;
  if (deg < 0.0) deg += 360.0;
  const float out = static_cast<float>(deg);
  return out >= 360.f ? 0.f : out;  // 359.99999999 rounds up to 360 in float
}

}  // namespace bowg
