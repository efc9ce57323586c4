// toMono8 and the message conversions: every supported encoding, zero copy
// for mono8, compressed images, clear errors.
#include "bowg_ros/image_conversion.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "encoded_test_images.h"

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
    } catch (const BadImage& x) {
      EXPECT_NE(std::string(x.what()).find(std::string("'") + e + "'"), std::string::npos)
          << x.what();
    }
  }
  for (const char* e : {"mono8", "mono16", "bgr8", "rgb8", "bgra8", "rgba8"}) {
    EXPECT_TRUE(isSupportedEncoding(e)) << e;
  }
}

TEST(ImageConversion, DataThatDoesNotMatchItsEncodingIsRejected) {
  EXPECT_THROW(toMono8(cv::Mat(2, 2, CV_8UC3), "mono8"), BadImage);
  EXPECT_THROW(toMono8(cv::Mat(2, 2, CV_8UC1), "bgr8"), BadImage);
  EXPECT_THROW(toMono8(cv::Mat(), "mono8"), BadImage);
}

// Hand-worked layouts: 4 x 3 bgr8 needs rows of 12 bytes and 3 rows.
TEST(ImageConversion, LayoutsThatCannotBeReadSafelyAreClassified) {
  using P = bowg::ImageProblem;
  EXPECT_TRUE(checkImageLayout(4, 3, 12, 36, "bgr8").ok());
  EXPECT_TRUE(checkImageLayout(4, 3, 16, 48, "bgr8").ok());  // padded rows
  EXPECT_EQ(checkImageLayout(4, 3, 11, 36, "bgr8").message(),
            "malformed: step 11 is shorter than a row of 4 pixels (12 bytes)");
  EXPECT_EQ(checkImageLayout(4, 3, 12, 35, "bgr8").message(),
            "malformed: data holds 35 bytes, height x step needs 36");
  EXPECT_EQ(checkImageLayout(4, 3, 0, 36, "bgr8").problem, P::kMalformed);
  EXPECT_EQ(checkImageLayout(0, 3, 12, 36, "bgr8").message(), "bad_header: empty image (0 x 3)");
  EXPECT_EQ(checkImageLayout(4, 3, 12, 36, "32FC1").problem, P::kUnsupportedFormat);
  // mono16: 2 bytes a pixel; no overflow with the largest values.
  EXPECT_EQ(checkImageLayout(5, 2, 9, 18, "mono16").problem, P::kMalformed);
  EXPECT_FALSE(checkImageLayout(0xffffffffu, 0xffffffffu, 0xffffffffu, 100, "rgba8").ok());
}

// OpenCV's Mat asserts that a 16-bit image's step is even: an odd step must
// be refused as malformed before the buffer is wrapped, not fail in OpenCV.
TEST(ImageConversion, Mono16WithAnOddStepIsMalformed) {
  for (const char* encoding : {"mono16", "16UC1"}) {
    const bowg::ImageCheck c = checkImageLayout(4, 3, 9, 27, encoding);
    EXPECT_EQ(c.problem, bowg::ImageProblem::kMalformed) << encoding << ": " << c.message();
  }
  EXPECT_TRUE(checkImageLayout(4, 3, 10, 30, "mono16").ok());
  EXPECT_TRUE(checkImageLayout(3, 3, 9, 27, "bgr8").ok());  // odd steps are fine for 8-bit
}

// An Image message of `rows` x `cols` pixels with `step` bytes per row.
sensor_msgs::Image message(const std::string& encoding, std::uint32_t rows, std::uint32_t cols,
                           std::uint32_t step, const std::vector<std::uint8_t>& data) {
  sensor_msgs::Image msg;
  msg.encoding = encoding;
  msg.height = rows;
  msg.width = cols;
  msg.step = step;
  msg.data = data;
  return msg;
}

TEST(ImageMessages, Mono8MessageIsWrappedNotCopiedAndHonoursItsStep) {
  // 2 x 2 pixels in rows of 3 bytes (one byte of padding per row).
  const sensor_msgs::Image msg = message("mono8", 2, 2, 3, {1, 2, 99, 3, 4, 99});
  const cv::Mat g = greyFromImage(msg);
  EXPECT_EQ(g.data, msg.data.data());
  ASSERT_EQ(g.size(), cv::Size(2, 2));
  EXPECT_EQ(g.at<std::uint8_t>(1, 0), 3);  // the padding byte is skipped
  EXPECT_EQ(g.at<std::uint8_t>(1, 1), 4);
}

TEST(ImageMessages, ColourAnd16BitMessagesAreConverted) {
  // One pure red pixel in BGR order: 0.299 * 255 = 76.2 -> 76.
  EXPECT_EQ(greyFromImage(message("bgr8", 1, 1, 3, {0, 0, 255})).at<std::uint8_t>(0, 0), 76);
  // 16UC1 reads as mono16: 0x1234 (little endian bytes 34 12) keeps the high
  // byte 0x12 = 18 (0x1234 / 256 = 18.2).
  EXPECT_EQ(greyFromImage(message("16UC1", 1, 1, 2, {0x34, 0x12})).at<std::uint8_t>(0, 0), 18);
  EXPECT_EQ(greyFromImage(message("8UC1", 1, 1, 1, {200})).at<std::uint8_t>(0, 0), 200);
}

TEST(ImageMessages, Mono16MessagesWithAnOddStepAreRefusedAsMalformed) {
  try {
    greyFromImage(message("mono16", 3, 4, 9, std::vector<std::uint8_t>(27, 1)));
    ADD_FAILURE() << "odd mono16 step accepted";
  } catch (const BadImage& e) {
    EXPECT_EQ(e.problem(), bowg::ImageProblem::kMalformed) << e.what();
  }
}

TEST(ImageMessages, OversizeMessagesAreTooLarge) {
  bowg::FeatureOptions o;
  o.max_image_pixels = 4 * 3 - 1;
  const sensor_msgs::Image msg = message("mono8", 3, 4, 4, std::vector<std::uint8_t>(12, 1));
  EXPECT_TRUE(checkImage(msg, bowg::FeatureOptions()).ok());
  EXPECT_EQ(checkImage(msg, o).problem, bowg::ImageProblem::kTooLarge);
}

TEST(ImageMessages, MalformedMessagesAreRefusedBeforeTheBufferIsRead) {
  try {
    greyFromImage(message("mono8", 2, 2, 2, {1, 2, 3}));  // 3 bytes, 2 x 2 needed
    ADD_FAILURE() << "short data accepted";
  } catch (const BadImage& e) {
    EXPECT_NE(std::string(e.what()).find("height x step needs 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(greyFromImage(message("yuv422", 1, 1, 2, {1, 2})), BadImage);
  EXPECT_THROW(greyFromImage(message("mono8", 0, 0, 0, {})), BadImage);
}

TEST(ImageMessages, CompressedImagesDecodeToTheirGreyPixels) {
  // PNG is lossless: the decoded grey image is the encoded one exactly.
  cv::Mat grey(3, 4, CV_8UC1);
  for (int i = 0; i < 12; ++i) grey.data[i] = static_cast<std::uint8_t>(20 * i);
  sensor_msgs::CompressedImage msg;
  msg.format = "mono8; png compressed";
  ASSERT_TRUE(cv::imencode(".png", grey, msg.data));
  const cv::Mat g = greyFromCompressed(msg);
  ASSERT_EQ(g.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(g != grey), 0);
  // A colour PNG is read as grey with the luma weights: red -> 76.
  const cv::Mat red(1, 1, CV_8UC3, cv::Scalar(0, 0, 255));
  ASSERT_TRUE(cv::imencode(".png", red, msg.data));
  EXPECT_EQ(greyFromCompressed(msg).at<std::uint8_t>(0, 0), 76);
}

TEST(ImageMessages, UndecodableCompressedDataNamesItsFormat) {
  sensor_msgs::CompressedImage msg;
  msg.format = "jpeg";
  msg.data = {0xFF, 0xD8, 0x00, 0x01};  // a JPEG marker, then nothing usable
  try {
    greyFromCompressed(msg);
    ADD_FAILURE() << "garbage decoded";
  } catch (const BadImage& e) {
    EXPECT_NE(std::string(e.what()).find("format 'jpeg'"), std::string::npos) << e.what();
  }
  msg.data.clear();
  EXPECT_THROW(greyFromCompressed(msg), BadImage);
}

sensor_msgs::CompressedImage compressed(const std::vector<std::uint8_t>& data) {
  sensor_msgs::CompressedImage msg;
  msg.format = "jpeg";
  msg.data = data;
  return msg;
}

bowg::ImageProblem problemOfDecoding(const sensor_msgs::CompressedImage& msg) {
  try {
    greyFromCompressed(msg);
  } catch (const BadImage& e) {
    return e.problem();
  }
  return bowg::ImageProblem::kNone;
}

// Each refusal has its reason; the header check alone gives the same one
// (what the nodelet's callback counts before queuing the frame).
TEST(ImageMessages, BadCompressedImagesAreClassifiedBeforeDecoding) {
  using P = bowg::ImageProblem;
  const bowg::FeatureOptions o;
  const sensor_msgs::CompressedImage truncated = compressed(bowg::test::truncatedJpeg());
  EXPECT_EQ(problemOfDecoding(truncated), P::kTruncated);
  EXPECT_EQ(checkCompressed(truncated, o).problem, P::kTruncated);
  const sensor_msgs::CompressedImage huge = compressed(bowg::test::pngDeclaring(30000, 30000));
  EXPECT_EQ(problemOfDecoding(huge), P::kTooLarge);
  const bowg::ImageCheck c = checkCompressed(huge, o);
  EXPECT_EQ(c.problem, P::kTooLarge);
  EXPECT_NE(c.detail.find("format 'jpeg'"), std::string::npos) << c.detail;
  EXPECT_EQ(problemOfDecoding(compressed({})), P::kEmpty);
  EXPECT_EQ(checkCompressed(compressed({}), o).problem, P::kEmpty);
  const sensor_msgs::CompressedImage whole =
      compressed(bowg::test::encodeImage(bowg::test::noiseImage(32, 24), ".jpg"));
  EXPECT_TRUE(checkCompressed(whole, o).ok());
  EXPECT_EQ(problemOfDecoding(whole), P::kNone);
}

}  // namespace
}  // namespace bowg_ros
