// Reading image-folder files for the offline tools: good images decode to
// grey; empty, garbage, truncated JPEG and oversized files are refused with
// a reason (the tools then skip and count them).
#include "bowg_evaluation/image_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

namespace bowg {
namespace eval {
namespace {

std::string path(const std::string& name) {
  return std::string(BOWG_TEST_OUTPUT_DIR) + "/image_file_" + name;
}

void writeBytes(const std::string& p, const std::vector<unsigned char>& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

std::vector<unsigned char> encoded(const cv::Mat& image, const std::string& ext) {
  std::vector<unsigned char> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes));
  return bytes;
}

std::string refusal(const std::string& p, const FeatureOptions& options = FeatureOptions()) {
  std::string why;
  const cv::Mat m = readGreyImage(p, options, &why);
  EXPECT_TRUE(m.empty()) << p;
  return why;
}

TEST(ImageFile, DecodesGreyAndColourImagesToGrey) {
  cv::Mat colour(48, 64, CV_8UC3, cv::Scalar(10, 200, 30));
  writeBytes(path("colour.png"), encoded(colour, ".png"));
  std::string why;
  const cv::Mat grey = readGreyImage(path("colour.png"), FeatureOptions(), &why);
  ASSERT_FALSE(grey.empty()) << why;
  EXPECT_EQ(grey.type(), CV_8UC1);
  EXPECT_EQ(grey.size(), cv::Size(64, 48));
  writeBytes(path("whole.jpg"), encoded(colour, ".jpg"));
  EXPECT_FALSE(readGreyImage(path("whole.jpg"), FeatureOptions(), &why).empty()) << why;
}

TEST(ImageFile, RefusesEmptyGarbageTruncatedAndOversizedFiles) {
  EXPECT_EQ(refusal(path("absent.png")), "cannot open the file");
  writeBytes(path("empty.png"), {});
  EXPECT_EQ(refusal(path("empty.png")), "the file is empty");
  writeBytes(path("garbage.png"), {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'});
  EXPECT_EQ(refusal(path("garbage.png")), "not an image OpenCV can decode");
  // A JPEG cut in half: libjpeg would decode the top and fill the rest grey.
  cv::Mat noise(120, 160, CV_8UC1);
  cv::randu(noise, 0, 255);
  std::vector<unsigned char> jpeg = encoded(noise, ".jpg");
  jpeg.resize(jpeg.size() / 2);
  writeBytes(path("truncated.jpg"), jpeg);
  EXPECT_EQ(refusal(path("truncated.jpg")), "truncated JPEG (no end-of-image marker)");
  // 4097 x 4097 compresses to a few kB but would decode to 16 MP: above the
  // default max_image_pixels (4096 x 4096), refused by OpenCV's header check
  // or after decoding.
  writeBytes(path("huge.png"), encoded(cv::Mat(4097, 4097, CV_8UC1, cv::Scalar(0)), ".png"));
  EXPECT_NE(refusal(path("huge.png")).find("max_image_pixels 16777216"), std::string::npos)
      << refusal(path("huge.png"));
}

TEST(ImageFile, TheSizeLimitIsTheConfiguredOne) {
  writeBytes(path("frame.png"), encoded(cv::Mat(48, 64, CV_8UC1, cv::Scalar(9)), ".png"));
  FeatureOptions o;
  o.max_image_pixels = 64 * 48;  // exactly the frame: accepted
  std::string why;
  EXPECT_FALSE(readGreyImage(path("frame.png"), o, &why).empty()) << why;
  o.max_image_pixels = 64 * 48 - 1;
  EXPECT_EQ(refusal(path("frame.png"), o),
            "64 x 48 = 3072 pixels, more than max_image_pixels 3071");
}

}  // namespace
}  // namespace eval
}  // namespace bowg
