// KeyframeThumbnails: size, round trip, memory, disabled.
#include "bowg_ros/keyframe_thumbnails.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace bowg_ros {
namespace {

/// 640 x 480 grey: a dark left half and a bright right half.
cv::Mat halves() {
  cv::Mat m(480, 640, CV_8UC1, cv::Scalar(30));
  m(cv::Rect(320, 0, 320, 480)).setTo(220);
  return m;
}

TEST(KeyframeThumbnails, RestoresTheImageAtItsOriginalSize) {
  KeyframeThumbnails t;  // longest side 240: 240 x 180 kept
  t.add(7, halves());
  ASSERT_EQ(t.size(), 1u);
  const cv::Mat r = t.restore(7);
  ASSERT_EQ(r.size(), cv::Size(640, 480));
  ASSERT_EQ(r.type(), CV_8UC1);
  // Far from the edge the halves come back within JPEG error.
  EXPECT_NEAR(r.at<std::uint8_t>(240, 100), 30, 4);
  EXPECT_NEAR(r.at<std::uint8_t>(240, 540), 220, 4);
  EXPECT_TRUE(t.restore(8).empty());  // never added
}

TEST(KeyframeThumbnails, CostsAFewKilobytesPerKeyframe) {
  KeyframeThumbnails t;
  cv::Mat noise(480, 640, CV_8UC1);
  cv::randu(noise, 0, 255);  // the worst case for JPEG
  t.add(0, noise);
  // 240 x 180 of noise at quality 80: well under the 43 kB of raw pixels.
  EXPECT_GT(t.bytes(), 1000u);
  EXPECT_LT(t.bytes(), 240u * 180u);
  const std::size_t one = t.bytes();
  t.add(0, noise);  // replacing does not count twice
  EXPECT_EQ(t.bytes(), one);
  t.add(1, halves());
  EXPECT_GT(t.bytes(), one);
  t.clear();
  EXPECT_EQ(t.size(), 0u);
  EXPECT_EQ(t.bytes(), 0u);
}

TEST(KeyframeThumbnails, SmallImagesKeepTheirSizeAndZeroKeepsNone) {
  KeyframeThumbnails t;
  const cv::Mat small(100, 200, CV_8UC1, cv::Scalar(128));
  t.add(1, small);
  EXPECT_EQ(t.restore(1).size(), cv::Size(200, 100));
  ThumbnailOptions off;
  off.max_side = 0;
  KeyframeThumbnails none(off);
  none.add(1, halves());
  EXPECT_EQ(none.size(), 0u);
  EXPECT_TRUE(none.restore(1).empty());
  ThumbnailOptions bad;
  bad.max_side = -1;
  EXPECT_THROW(KeyframeThumbnails{bad}, std::invalid_argument);
  bad.max_side = 10;
  bad.jpeg_quality = 0;
  EXPECT_THROW(KeyframeThumbnails{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace bowg_ros
