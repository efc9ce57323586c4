// Byte <-> bit packing of OpenCV descriptor rows (types.h: byte j holds bits
// 8j..8j+7, little endian).
#include <gtest/gtest.h>

#include <stdexcept>

#include "bowg/features/descriptor_conversion.h"

namespace bowg {
namespace {

TEST(DescriptorConversion, ByteJHoldsBits8jTo8jPlus7) {
  std::uint8_t bytes[kDescriptorBytes] = {};
  bytes[0] = 0x01;   // bit 0
  bytes[1] = 0x80;   // bit 8 + 7 = 15
  bytes[8] = 0x02;   // bit 64 + 1 = 65 -> block 1, bit 1
  bytes[31] = 0x80;  // bit 248 + 7 = 255 -> block 3, bit 63
  const Descriptor d = descriptorFromBytes(bytes);
  // Block 0 = 2^0 + 2^15 = 0x8001.
  EXPECT_EQ(d.bits[0], 0x8001u);
  EXPECT_EQ(d.bits[1], 0x2u);
  EXPECT_EQ(d.bits[2], 0u);
  EXPECT_EQ(d.bits[3], 0x8000000000000000ull);
}

TEST(DescriptorConversion, MatRoundTrip) {
  cv::Mat mat(3, kDescriptorBytes, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(mat, cv::RNG::UNIFORM, 0, 256);
  const std::vector<Descriptor> d = descriptorsFromMat(mat);
  ASSERT_EQ(d.size(), 3u);
  const cv::Mat back = descriptorsToMat(d);
  EXPECT_EQ(cv::norm(mat, back, cv::NORM_INF), 0.0);
  // Hamming distance equals OpenCV's on the byte rows.
  EXPECT_EQ(hammingDistance(d[0], d[1]),
            static_cast<int>(cv::norm(mat.row(0), mat.row(1), cv::NORM_HAMMING)));
}

TEST(DescriptorConversion, EmptyAndWrongShapes) {
  EXPECT_TRUE(descriptorsFromMat(cv::Mat()).empty());
  EXPECT_TRUE(descriptorsToMat({}).empty());
  EXPECT_THROW(descriptorsFromMat(cv::Mat(2, 31, CV_8UC1)), std::invalid_argument);
  EXPECT_THROW(descriptorsFromMat(cv::Mat(2, 32, CV_32FC1)), std::invalid_argument);
}

}  // namespace
}  // namespace bowg
