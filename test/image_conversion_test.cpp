// toMono8: every supported encoding, zero copy for mono8, clear errors.
#include "bowg_ros/image_conversion.h"

#include <gtest/gtest.h>

namespace bowg_ros {
namespace {

TEST(ImageConversion, Mono8IsSharedNotCopied) {
  cv::Mat img(4, 6, CV_8UC1, cv::Scalar(7));
  const cv::Mat grey = toMono8(img, "mono8");
  EXPECT_EQ(grey.data, img.data);
}

TEST(ImageConversion, Mono16KeepsTheHighByte) {
  cv::Mat img(2, 2, CV_16UC1);
  img.at<std::uint16_t>(0, 0) = 0;
  img.at<std::uint16_t>(0, 1) = 256;    // 256 / 256 = 1
  img.at<std::uint16_t>(1, 0) = 32768;  // 32768 / 256 = 128
  img.at<std::uint16_t>(1, 1) = 65535;  // 65535 / 256 = 255.996 -> 255 (saturated)
  const cv::Mat g = toMono8(img, "mono16");
  ASSERT_EQ(g.type(), CV_8UC1);
  EXPECT_EQ(g.at<std::uint8_t>(0, 0), 0);
  EXPECT_EQ(g.at<std::uint8_t>(0, 1), 1);
  EXPECT_EQ(g.at<std::uint8_t>(1, 0), 128);
  EXPECT_EQ(g.at<std::uint8_t>(1, 1), 255);
}

// Luma Y = 0.299 R + 0.587 G + 0.114 B (OpenCV's weights). A pure red pixel
// gives 0.299 * 255 = 76.2 -> 76; pure blue 0.114 * 255 = 29.1 -> 29.
TEST(ImageConversion, ColourOrderIsRespected) {
  cv::Mat bgr(1, 2, CV_8UC3);
  bgr.at<cv::Vec3b>(0, 0) = cv::Vec3b(0, 0, 255);  // red in BGR
  bgr.at<cv::Vec3b>(0, 1) = cv::Vec3b(255, 0, 0);  // blue in BGR
  cv::Mat g = toMono8(bgr, "bgr8");
  EXPECT_EQ(g.at<std::uint8_t>(0, 0), 76);
  EXPECT_EQ(g.at<std::uint8_t>(0, 1), 29);
  // The same bytes read as RGB swap the two.
  g = toMono8(bgr, "rgb8");
  EXPECT_EQ(g.at<std::uint8_t>(0, 0), 29);
  EXPECT_EQ(g.at<std::uint8_t>(0, 1), 76);

  cv::Mat bgra(1, 1, CV_8UC4, cv::Scalar(0, 0, 255, 10));  // red, alpha 10
  EXPECT_EQ(toMono8(bgra, "bgra8").at<std::uint8_t>(0, 0), 76);
  EXPECT_EQ(toMono8(bgra, "rgba8").at<std::uint8_t>(0, 0), 29);
}

TEST(ImageConversion, UnsupportedEncodingsNameTheEncoding) {
  for (const char* e : {"bayer_rggb8", "32FC1", "yuv422", "16UC3", ""}) {
    EXPECT_FALSE(isSupportedEncoding(e)) << e;
    try {
      toMono8(cv::Mat(2, 2, CV_8UC1), e);
      ADD_FAILURE() << e << " accepted";
    } catch (const UnsupportedEncoding& x) {
      EXPECT_NE(std::string(x.what()).find(std::string("'") + e + "'"), std::string::npos)
          << x.what();
    }
  }
  for (const char* e : {"mono8", "mono16", "bgr8", "rgb8", "bgra8", "rgba8"}) {
    EXPECT_TRUE(isSupportedEncoding(e)) << e;
  }
}

TEST(ImageConversion, DataThatDoesNotMatchItsEncodingIsRejected) {
  EXPECT_THROW(toMono8(cv::Mat(2, 2, CV_8UC3), "mono8"), UnsupportedEncoding);
  EXPECT_THROW(toMono8(cv::Mat(2, 2, CV_8UC1), "bgr8"), UnsupportedEncoding);
  EXPECT_THROW(toMono8(cv::Mat(), "mono8"), UnsupportedEncoding);
}

// Hand-worked layouts: 4 x 3 bgr8 needs rows of 12 bytes and 3 rows.
TEST(ImageConversion, LayoutsThatCannotBeReadSafelyAreNamed) {
  EXPECT_EQ(imageLayoutProblem(4, 3, 12, 36, "bgr8"), "");
  EXPECT_EQ(imageLayoutProblem(4, 3, 16, 48, "bgr8"), "");  // padded rows
  EXPECT_EQ(imageLayoutProblem(4, 3, 11, 36, "bgr8"),
            "step 11 is shorter than a row of 4 bgr8 pixels (12 bytes)");
  EXPECT_EQ(imageLayoutProblem(4, 3, 12, 35, "bgr8"), "data holds 35 bytes, height x step needs 36");
  EXPECT_EQ(imageLayoutProblem(4, 3, 0, 36, "bgr8"),
            "step 0 is shorter than a row of 4 bgr8 pixels (12 bytes)");
  EXPECT_EQ(imageLayoutProblem(0, 3, 12, 36, "bgr8"), "empty image (0 x 3)");
  EXPECT_EQ(imageLayoutProblem(4, 3, 12, 36, "32FC1"), "unsupported encoding '32FC1'");
  // mono16: 2 bytes a pixel; no overflow with the largest values.
  EXPECT_EQ(imageLayoutProblem(5, 2, 9, 18, "mono16"),
            "step 9 is shorter than a row of 5 mono16 pixels (10 bytes)");
  EXPECT_NE(imageLayoutProblem(0xffffffffu, 0xffffffffu, 0xffffffffu, 100, "rgba8"), "");
}

}  // namespace
}  // namespace bowg_ros
