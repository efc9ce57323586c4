// Image dimensions read from the header before decoding, and truncated or
// foreign data told apart, for every format read (PNG, JPEG, BMP, PNM).
#include "bowg/features/image_header.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "encoded_test_images.h"

namespace bowg {
namespace {

using Bytes = std::vector<std::uint8_t>;

ImageCheck header(const Bytes& bytes, ImageHeader* h) {
  return readImageHeader(bytes.data(), bytes.size(), h);
}

ImageProblem problemOf(const Bytes& bytes) {
  ImageHeader h;
  return header(bytes, &h).problem;
}

TEST(ImageHeader, ReadsTheDimensionsOfEveryFormatRead) {
  const cv::Mat grey = test::noiseImage(64, 48);
  cv::Mat colour;
  cv::merge(std::vector<cv::Mat>{grey, grey, grey}, colour);
  for (const auto& c : {std::make_pair(".png", "PNG"), std::make_pair(".jpg", "JPEG"),
                        std::make_pair(".bmp", "BMP"), std::make_pair(".pgm", "PNM")}) {
    ImageHeader h;
    const ImageCheck check = header(test::encodeImage(grey, c.first), &h);
    ASSERT_TRUE(check.ok()) << c.first << ": " << check.message();
    EXPECT_EQ(h.format, c.second);
    EXPECT_EQ(h.width, 64u) << c.first;
    EXPECT_EQ(h.height, 48u) << c.first;
  }
  ImageHeader h;
  ASSERT_TRUE(header(test::encodeImage(colour, ".ppm"), &h).ok());
  EXPECT_EQ(h.width, 64u);
  ASSERT_TRUE(header(test::encodeImage(colour, ".bmp"), &h).ok());
  EXPECT_EQ(h.height, 48u);
}

TEST(ImageHeader, AHugeDeclaredPngIsReadFromItsIhdr) {
  const Bytes png = test::pngDeclaring(30000, 30000);
  ASSERT_LT(png.size(), 1000u);
  ImageHeader h;
  ASSERT_TRUE(header(png, &h).ok());
  EXPECT_EQ(h.width, 30000u);
  EXPECT_EQ(h.height, 30000u);
}

TEST(ImageHeader, TruncatedImagesOfEveryFormatAreTruncated) {
  EXPECT_EQ(problemOf(test::truncatedJpeg()), ImageProblem::kTruncated);
  const cv::Mat noise = test::noiseImage(64, 48);
  for (const char* ext : {".png", ".bmp", ".pgm"}) {
    Bytes b = test::encodeImage(noise, ext);
    b.resize(b.size() - 40);
    EXPECT_EQ(problemOf(b), ImageProblem::kTruncated) << ext;
  }
  // Zero padding after EOI is tolerated, as decoders do.
  Bytes padded = test::encodeImage(noise, ".jpg");
  padded.insert(padded.end(), 16, 0);
  EXPECT_TRUE(problemOf(padded) == ImageProblem::kNone);
}

TEST(ImageHeader, BrokenHeadersAreBadHeaders) {
  // A JPEG of SOI, a segment whose length runs past the data, EOI.
  EXPECT_EQ(problemOf({0xff, 0xd8, 0xff, 0xe0, 0x7f, 0xff, 0x00, 0xff, 0xd9}),
            ImageProblem::kBadHeader);
  // SOI, EOI: no frame at all.
  EXPECT_EQ(problemOf({0xff, 0xd8, 0xff, 0xd9}), ImageProblem::kBadHeader);
  // A PNG signature followed by IEND only.
  Bytes png = test::encodeImage(test::noiseImage(8, 8), ".png");
  png[12] = 'X';
  EXPECT_EQ(problemOf(png), ImageProblem::kBadHeader);
  EXPECT_EQ(problemOf(test::pngDeclaring(0, 10)), ImageProblem::kBadHeader);
  EXPECT_EQ(problemOf({'P', '5', ' ', 'x'}), ImageProblem::kBadHeader);
  EXPECT_EQ(problemOf({'B', 'M', 0, 0}), ImageProblem::kBadHeader);
}

TEST(ImageHeader, OtherFormatsAreUnsupportedAndEmptyDataIsEmpty) {
  EXPECT_EQ(problemOf({}), ImageProblem::kEmpty);
  ImageHeader h;
  const ImageCheck tiff = header({'I', 'I', '*', 0, 8, 0, 0, 0}, &h);
  EXPECT_EQ(tiff.problem, ImageProblem::kUnsupportedFormat);
  EXPECT_NE(tiff.detail.find("TIFF"), std::string::npos) << tiff.detail;
  EXPECT_EQ(problemOf({'G', 'I', 'F', '8', '9', 'a'}), ImageProblem::kUnsupportedFormat);
  EXPECT_EQ(problemOf({'P', '2', ' ', '1', ' ', '1', ' ', '9', ' ', '3'}),
            ImageProblem::kUnsupportedFormat);
  EXPECT_EQ(problemOf({'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'}),
            ImageProblem::kUnsupportedFormat);
}

}  // namespace
}  // namespace bowg
