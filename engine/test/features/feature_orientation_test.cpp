// Intensity-centroid orientation (Rosin; ORB Sec. 3.2).
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "bowg/features/orb_descriptor.h"
#include "bowg/features/orientation.h"
#include "feature_test_images.h"

namespace bowg {
namespace {

double angleDiff(double a, double b) {
  double d = std::fmod(std::fabs(a - b), 360.0);
  return d > 180.0 ? 360.0 - d : d;
}

TEST(Orientation, BrightSideGivesTheAngle) {
  // Bright right half (x > 20): m01 = 0 by symmetry, m10 > 0 -> 0 degrees.
  cv::Mat img(41, 41, CV_8UC1, cv::Scalar(0));
  img.colRange(21, 41).setTo(200);
  EXPECT_NEAR(intensityCentroidAngle(img, cv::Point2f(20, 20), 10), 0.0, 1e-4);
  // Bright bottom half (y > 20, y points down): m10 = 0, m01 > 0 -> 90.
  img.setTo(0);
  img.rowRange(21, 41).setTo(200);
  EXPECT_NEAR(intensityCentroidAngle(img, cv::Point2f(20, 20), 10), 90.0, 1e-4);
  // Bright top-left quadrant: m10 = m01 < 0 -> 225.
  img.setTo(0);
  img(cv::Rect(0, 0, 20, 20)).setTo(200);
  EXPECT_NEAR(intensityCentroidAngle(img, cv::Point2f(20, 20), 10), 225.0, 1e-4);
  // Flat patch: 0 by convention.
  img.setTo(50);
  EXPECT_EQ(intensityCentroidAngle(img, cv::Point2f(20, 20), 10), 0.f);
}

TEST(Orientation, DiscOfRadiusTwoByHand) {
  // radius 2: pixels with u^2 + v^2 <= 2 * 3 = 6, the 5x5 square without
  // its corners (8 > 6). One bright pixel at (u, v) = (2, 1) (5 <= 6):
  // m10 = 2 I, m01 = I -> atan2(1, 2) = 26.565 degrees.
  cv::Mat img(9, 9, CV_8UC1, cv::Scalar(0));
  img.at<std::uint8_t>(4 + 1, 4 + 2) = 100;
  EXPECT_NEAR(intensityCentroidAngle(img, cv::Point2f(4, 4), 2), 26.56505, 1e-4);
  // A corner pixel (2, 2) lies outside the disc: only (-1, 0) counts -> 180.
  img.setTo(0);
  img.at<std::uint8_t>(4 + 2, 4 + 2) = 250;
  img.at<std::uint8_t>(4 + 0, 4 - 1) = 10;
  EXPECT_NEAR(intensityCentroidAngle(img, cv::Point2f(4, 4), 2), 180.0, 1e-4);
}

// The moments pixel by pixel over the disc u^2 + v^2 <= r (r + 1), in 64
// bits, and the angle by the same formula.
float referenceAngle(const cv::Mat& img, int cx, int cy, int r) {
  long long m10 = 0, m01 = 0;
  for (int v = -r; v <= r; ++v)
    for (int u = -r; u <= r; ++u) {
      if (u * u + v * v > r * (r + 1)) continue;
      const int value = img.at<std::uint8_t>(cy + v, cx + u);
      m10 += static_cast<long long>(u) * value;
      m01 += static_cast<long long>(v) * value;
    }
  if (m10 == 0 && m01 == 0) return 0.f;
  double deg = std::atan2(static_cast<double>(m01), static_cast<double>(m10)) * 180.0 / M_PI;
  if (deg < 0.0) deg += 360.0;
  const float out = static_cast<float>(deg);
  return out >= 360.f ? 0.f : out;
}

TEST(Orientation, EqualsThePixelByPixelMomentsAtEveryRadius) {
  // Rows of the disc are summed as runs (32-bit sums up to a half-width of
  // 1000, 64-bit beyond): the same moments as pixel by pixel.
  const cv::Mat img = test::texturedImage(160, 120, 80, 5);
  for (int r : {1, 2, 3, 7, 15, 19, 31}) {
    for (int k = 0; k < 20; ++k) {
      const int cx = 40 + 4 * k, cy = 40 + 2 * k;
      EXPECT_EQ(intensityCentroidAngle(img, cv::Point2f(cx, cy), r), referenceAngle(img, cx, cy, r))
          << "radius " << r << " at " << cx << ", " << cy;
    }
  }
  cv::Mat big;
  cv::resize(img, big, cv::Size(2010, 2010), 0, 0, cv::INTER_NEAREST);
  EXPECT_EQ(intensityCentroidAngle(big, cv::Point2f(1004, 1004), 1002),
            referenceAngle(big, 1004, 1004, 1002));
}

TEST(Orientation, ExactNinetyDegreeRotation) {
  const cv::Mat img = test::texturedImage(120, 100, 60, 3);
  cv::Mat rot;
  cv::rotate(img, rot, cv::ROTATE_90_CLOCKWISE);
  for (int k = 0; k < 20; ++k) {
    const cv::Point2f p(30 + 3 * k, 30 + 2 * k);
    // Clockwise on screen: (x, y) -> (H - 1 - y, x), vector (dx, dy) -> (-dy, dx),
    // i.e. +90 degrees in image axes.
    const cv::Point2f q(img.rows - 1 - p.y, p.x);
    const double a = intensityCentroidAngle(img, p, 15);
    const double b = intensityCentroidAngle(rot, q, 15);
    EXPECT_LT(angleDiff(b, a + 90.0), 1e-3) << "point " << k;
  }
}

TEST(Orientation, MatchesOrbDetectorAtLevelZero) {
  // ORB's own angles (octave 0) come from its circular patch of radius 15;
  // ours differs only at a few rim pixels.
  const cv::Mat img = test::texturedImage(320, 240, 150, 11);
  cv::Ptr<cv::ORB> orb = cv::ORB::create(500);
  std::vector<cv::KeyPoint> kps;
  orb->detect(img, kps);
  int compared = 0;
  int close = 0;
  for (const cv::KeyPoint& kp : kps) {
    if (kp.octave != 0) continue;
    ++compared;
    if (angleDiff(kp.angle, intensityCentroidAngle(img, kp.pt, kOrbHalfPatch)) < 3.0) ++close;
  }
  ASSERT_GT(compared, 50);
  EXPECT_GE(close, compared * 9 / 10) << close << " of " << compared;
}

TEST(Orientation, RejectsDiscOutsideImage) {
  const cv::Mat img(30, 30, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(intensityCentroidAngle(img, cv::Point2f(5, 15), 10), std::invalid_argument);
  EXPECT_THROW(intensityCentroidAngle(img, cv::Point2f(15, 20), 10), std::invalid_argument);
  EXPECT_NO_THROW(intensityCentroidAngle(img, cv::Point2f(10, 19), 10));
  EXPECT_THROW(intensityCentroidAngle(cv::Mat(30, 30, CV_8UC3), cv::Point2f(15, 15), 5),
               std::invalid_argument);
}

}  // namespace
}  // namespace bowg
