// Intensity-centroid orientation (Rosin; ORB Sec. 3.2).
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/features2d.hpp>
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
