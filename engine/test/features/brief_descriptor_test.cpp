// Plain BRIEF as DVision::BRIEF computes it for VINS (facts and sources in
// brief_descriptor.h): bit order, comparison direction, truncation,
// smoothing, and steering.
#include "bowg/features/brief_descriptor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "bowg/features/brief_pattern.h"
#include "bowg/features/descriptor_conversion.h"
#include "bowg/features/orientation.h"
#include "feature_test_images.h"

namespace bowg {
namespace {

// I(x, y) = 10 y + x: every pixel distinct, readable by hand.
cv::Mat tinyImage(int size) {
  cv::Mat img(size, size, CV_8UC1);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x)
      img.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(10 * y + x);
  }
  return img;
}

bool bit(const Descriptor& d, int i) { return (d.bits[i / 64] >> (i % 64)) & 1u; }

TEST(BriefDescriptor, HandWorkedBitsAndBitOrder) {
  // 5x5 image, keypoint (2, 2); offsets are (dx, dy) relative to it.
  const cv::Mat img = tinyImage(5);
  // Unset tests compare (0,0) with itself: I(2,2) < I(2,2) is false -> 0.
  std::vector<cv::Vec4i> pattern(256, cv::Vec4i(0, 0, 0, 0));
  pattern[0] = {-1, 0, 1, 0};     // I(1,2)=21 < I(3,2)=23 -> 1
  pattern[1] = {1, 0, -1, 0};     // 23 < 21 -> 0 (first point on the left)
  pattern[2] = {0, -1, 0, 1};     // I(2,1)=12 < I(2,3)=32 -> 1
  pattern[3] = {0, 0, 0, 0};      // 22 < 22 -> 0 (strictly less)
  pattern[64] = {-2, -2, 2, 2};   // I(0,0)=0 < I(4,4)=44 -> 1 (block 1, bit 0)
  pattern[254] = {-2, 2, 2, -2};  // I(0,4)=40 < I(4,0)=4 -> 0
  pattern[255] = {2, -2, -2, 2};  // 4 < 40 -> 1 (block 3, bit 63)
  const auto d = computeBriefDescriptors(img, pattern, {cv::KeyPoint(2, 2, 1)}, false);
  ASSERT_EQ(d.size(), 1u);
  // Bits 0 and 2 -> block 0 = 0b101 = 5.
  EXPECT_EQ(d[0].bits[0], 5u);
  EXPECT_EQ(d[0].bits[1], 1u);
  EXPECT_EQ(d[0].bits[2], 0u);
  EXPECT_EQ(d[0].bits[3], 0x8000000000000000ull);
  // The same bits as OpenCV bytes: byte 0 = 5, byte 8 = 1, byte 31 = 0x80.
  const cv::Mat bytes = descriptorsToMat(d);
  EXPECT_EQ(bytes.at<std::uint8_t>(0, 0), 5);
  EXPECT_EQ(bytes.at<std::uint8_t>(0, 8), 1);
  EXPECT_EQ(bytes.at<std::uint8_t>(0, 31), 0x80);
}

TEST(BriefDescriptor, FractionalKeypointsTruncateTowardZero) {
  // 7x7, I(x,y) = 10y + x except I(3,3) = 0. Keypoint (2.6, 3.0), test
  // (0,0) vs (-1,0): truncation samples I(2,3)=32 vs I(1,3)=31 -> 32 < 31
  // is 0; rounding would sample I(3,3)=0 vs I(2,3)=32 -> 1.
  cv::Mat img = tinyImage(7);
  img.at<std::uint8_t>(3, 3) = 0;
  std::vector<cv::Vec4i> pattern = {{0, 0, -1, 0}, {-1, 0, 0, 0}};
  const auto d = computeBriefDescriptors(img, pattern, {cv::KeyPoint(2.6f, 3.f, 1)}, false);
  EXPECT_FALSE(bit(d[0], 0));
  EXPECT_TRUE(bit(d[0], 1));  // 31 < 32
}

TEST(BriefDescriptor, SmoothingIsGaussian9x9Sigma2) {
  // Impulse of 255 at the centre. Normalised 1-D kernel g(k) ~ exp(-k^2/8),
  // k = -4..4: sum = 1 + 2 (0.8825 + 0.6065 + 0.3247 + 0.1353) = 4.8980,
  // g(0) = 0.20417, g(4) = 0.1353 / 4.898 = 0.027624.
  // Centre: 255 g(0)^2 = 10.63; at (4, 0): 255 g(0) g(4) = 1.44; at (5, 0)
  // the 9-tap kernel no longer reaches: 0.
  cv::Mat img(21, 21, CV_8UC1, cv::Scalar(0));
  img.at<std::uint8_t>(10, 10) = 255;
  const cv::Mat s = smoothForBrief(img);
  EXPECT_NEAR(s.at<std::uint8_t>(10, 10), 10.63, 0.6);
  EXPECT_NEAR(s.at<std::uint8_t>(10, 14), 1.44, 0.6);
  EXPECT_EQ(s.at<std::uint8_t>(10, 15), 0);
  EXPECT_EQ(s.at<std::uint8_t>(15, 10), 0);
}

TEST(BriefDescriptor, RejectsTestsOutsideTheImage) {
  const cv::Mat img = tinyImage(5);
  const std::vector<cv::Vec4i> pattern = {{-2, 0, 2, 0}};
  EXPECT_THROW(computeBriefDescriptors(img, pattern, {cv::KeyPoint(1, 2, 1)}, false),
               std::invalid_argument);
  EXPECT_THROW(computeBriefDescriptors(img, pattern, {cv::KeyPoint(3, 2, 1)}, false),
               std::invalid_argument);
  // (x + dx) in (-1, 0) truncates to 0 in DVision but lies outside.
  EXPECT_THROW(computeBriefDescriptors(img, pattern, {cv::KeyPoint(1.5f, 2, 1)}, false),
               std::invalid_argument);
  EXPECT_THROW(computeBriefDescriptors(img, std::vector<cv::Vec4i>(257), {}, false),
               std::invalid_argument);
}

TEST(BriefDescriptor, PatternRadius) {
  const std::vector<cv::Vec4i> pattern = {{3, -4, 1, 0}, {0, 2, -2, 2}};
  EXPECT_EQ(briefPatternRadius(pattern, false), 4);  // max |coordinate|
  EXPECT_EQ(briefPatternRadius(pattern, true), 5);   // |(3, -4)| = 5
  const std::vector<cv::Vec4i> diag = {{2, 2, 0, 0}};
  EXPECT_EQ(briefPatternRadius(diag, true), 3);  // ceil(2 sqrt 2 = 2.83)
}

TEST(BriefDescriptor, SteeringByZeroIsUprightAndByNinetyRotatesOffsets) {
  const cv::Mat img = smoothForBrief(test::texturedImage(100, 100, 50, 4));
  cv::RNG rng(5);
  std::vector<cv::Vec4i> pattern(256);
  for (cv::Vec4i& p : pattern) {
    p = {rng.uniform(-12, 13), rng.uniform(-12, 13), rng.uniform(-12, 13), rng.uniform(-12, 13)};
  }
  // 90 degrees: (x, y) -> (x cos - y sin, x sin + y cos) = (-y, x).
  std::vector<cv::Vec4i> turned(256);
  for (int i = 0; i < 256; ++i) {
    turned[i] = {-pattern[i][1], pattern[i][0], -pattern[i][3], pattern[i][2]};
  }
  const cv::KeyPoint kp0(50, 50, 31, 0.f), kp90(50, 50, 31, 90.f);
  const auto upright = computeBriefDescriptors(img, pattern, {kp0}, false);
  EXPECT_EQ(computeBriefDescriptors(img, pattern, {kp0}, true)[0], upright[0]);
  EXPECT_EQ(computeBriefDescriptors(img, pattern, {kp90}, true)[0],
            computeBriefDescriptors(img, turned, {kp0}, false)[0]);
  // Steering off ignores the angle.
  EXPECT_EQ(computeBriefDescriptors(img, pattern, {kp90}, false)[0], upright[0]);
}

TEST(BriefDescriptor, SteeredSurvivesNinetyDegreeRotationUprightDoesNot) {
  const cv::Mat img = test::texturedImage(200, 160, 100, 8);
  cv::Mat rot;
  cv::rotate(img, rot, cv::ROTATE_90_CLOCKWISE);
  // Smoothing commutes with the rotation (symmetric kernel).
  const cv::Mat s_img = smoothForBrief(img), s_rot = smoothForBrief(rot);
  cv::RNG rng(6);
  std::vector<cv::Vec4i> pattern(256);
  for (cv::Vec4i& p : pattern) {
    p = {rng.uniform(-16, 17), rng.uniform(-16, 17), rng.uniform(-16, 17), rng.uniform(-16, 17)};
  }
  const int r = briefPatternRadius(pattern, true);
  double sum_steer = 0, sum_up = 0;
  int n = 0;
  for (int y = r; y < img.rows - r; y += 9) {
    for (int x = r; x < img.cols - r; x += 9) {
      const cv::Point2f p(x, y), q(img.rows - 1 - y, x);
      const cv::KeyPoint ka(p, 31, intensityCentroidAngle(img, p, 16));
      const cv::KeyPoint kb(q, 31, intensityCentroidAngle(rot, q, 16));
      sum_steer += hammingDistance(computeBriefDescriptors(s_img, pattern, {ka}, true)[0],
                                   computeBriefDescriptors(s_rot, pattern, {kb}, true)[0]);
      sum_up += hammingDistance(computeBriefDescriptors(s_img, pattern, {ka}, false)[0],
                                computeBriefDescriptors(s_rot, pattern, {kb}, false)[0]);
      ++n;
    }
  }
  ASSERT_GT(n, 50);
  EXPECT_LT(sum_steer / n, 10.0);
  EXPECT_GT(sum_up / n, 60.0);
}

// The shared VINS pattern on a horizontal ramp I(x, y) = 2x, keypoint (50, 50):
// after smoothing the ramp is unchanged inside, so bit i = (x1 < x2).
TEST(BriefDescriptor, VinsPatternOnARamp) {
  const std::string path = std::string(BOWG_SHARED_DATA_DIR) + "/vocabularies/brief_pattern.yml";
  if (!std::ifstream(path).good()) GTEST_SKIP() << "shared data absent: " << path;
  const std::vector<cv::Vec4i> pattern = loadBriefPattern(path);
  cv::Mat ramp(100, 100, CV_8UC1);
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) ramp.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(2 * x);
  }
  const auto d =
      computeBriefDescriptors(smoothForBrief(ramp), pattern, {cv::KeyPoint(50, 50, 1)}, false);
  // First pairs of the file (x1 y1 x2 y2), by hand:
  // 0: (0,-10) (0,-6):  I = 100 vs 100 -> 0
  // 1: (4,12) (0,6):    108 vs 100     -> 0
  // 2: (11,13) (13,10): 122 vs 126     -> 1
  // 3: (-4,8) (-6,9):   92 vs 88       -> 0
  EXPECT_FALSE(bit(d[0], 0));
  EXPECT_FALSE(bit(d[0], 1));
  EXPECT_TRUE(bit(d[0], 2));
  EXPECT_FALSE(bit(d[0], 3));
  for (int i = 0; i < 256; ++i) EXPECT_EQ(bit(d[0], i), pattern[i][0] < pattern[i][2]) << i;
}

}  // namespace
}  // namespace bowg
