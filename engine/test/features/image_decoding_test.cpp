// Checked decoding: images over max_image_pixels are refused from their
// header (bounded memory and time), truncated or corrupt ones are refused
// with their reason, and a folder entry that is not a regular file is
// refused without blocking or reading an endless device.
#include "bowg/features/image_decoding.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "encoded_test_images.h"

namespace bowg {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::string path(const std::string& name) {
  return std::string(BOWG_TEST_OUTPUT_DIR) + "/image_decoding_" + name;
}

cv::Mat decode(const Bytes& b, ImageCheck* check, const FeatureOptions& o = FeatureOptions()) {
  return decodeGreyImage(b.data(), b.size(), o, check);
}

// The process's peak resident set in kB (VmHWM); -1 where not told.
long peakKb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.compare(0, 6, "VmHWM:") == 0) return std::stol(line.substr(6));
  }
  return -1;
}

// Resets the peak to the current resident set (clear_refs 5) so that the
// peak read afterwards is that of what follows; returns the baseline.
long resetPeakKb() {
  std::ofstream("/proc/self/clear_refs") << "5";
  return peakKb();
}

TEST(ImageDecoding, DecodesGreyAndColourImagesToGrey) {
  cv::Mat colour(48, 64, CV_8UC3, cv::Scalar(10, 200, 30));
  for (const char* ext : {".png", ".jpg", ".bmp", ".ppm"}) {
    ImageCheck check;
    const cv::Mat grey = decode(test::encodeImage(colour, ext), &check);
    ASSERT_TRUE(check.ok()) << ext << ": " << check.message();
    EXPECT_EQ(grey.type(), CV_8UC1);
    EXPECT_EQ(grey.size(), cv::Size(64, 48));
  }
}

TEST(ImageDecoding, AHugePngIsRefusedFromItsHeaderInBoundedMemoryAndTime) {
  const Bytes png = test::pngDeclaring(30000, 30000);  // 900 MP decoded
  const long before = resetPeakKb();
  const auto t0 = std::chrono::steady_clock::now();
  ImageCheck check;
  EXPECT_TRUE(decode(png, &check).empty());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(check.problem, ImageProblem::kTooLarge) << check.message();
  EXPECT_NE(check.detail.find("30000 x 30000"), std::string::npos) << check.detail;
  EXPECT_LT(seconds, 1.0);
  if (before > 0) EXPECT_LT(peakKb() - before, 100 * 1024) << "kB over the baseline";
}

TEST(ImageDecoding, TheSizeLimitIsTheConfiguredOne) {
  const Bytes png = test::encodeImage(cv::Mat(48, 64, CV_8UC1, cv::Scalar(9)), ".png");
  FeatureOptions o;
  o.max_image_pixels = 64 * 48;  // exactly the frame: accepted
  ImageCheck check;
  EXPECT_FALSE(decode(png, &check, o).empty()) << check.message();
  o.max_image_pixels = 64 * 48 - 1;
  EXPECT_TRUE(decode(png, &check, o).empty());
  EXPECT_EQ(check.message(),
            "too_large: PNG 64 x 48 = 3072 pixels, more than max_image_pixels 3071");
}

TEST(ImageDecoding, TruncatedAndCorruptImagesAreRefusedWithTheirReason) {
  ImageCheck check;
  EXPECT_TRUE(decode(test::truncatedJpeg(), &check).empty());
  EXPECT_EQ(check.problem, ImageProblem::kTruncated);
  // A whole PNG whose compressed pixel data is overwritten: the header is
  // fine, the decoder fails.
  Bytes png = test::encodeImage(test::noiseImage(64, 48), ".png");
  for (std::size_t i = 60; i < png.size() - 20; ++i) png[i] = 0x5a;
  EXPECT_TRUE(decode(png, &check).empty());
  EXPECT_EQ(check.problem, ImageProblem::kUndecodable) << check.message();
  EXPECT_TRUE(decode({}, &check).empty());
  EXPECT_EQ(check.problem, ImageProblem::kEmpty);
}

TEST(ImageDecoding, FilesAreReadAndRefusedByReason) {
  test::writeBytes(path("frame.png"), test::encodeImage(test::noiseImage(64, 48), ".png"));
  ImageCheck check;
  EXPECT_EQ(readGreyImageFile(path("frame.png"), FeatureOptions(), &check).size(),
            cv::Size(64, 48))
      << check.message();
  test::writeBytes(path("empty.png"), {});
  EXPECT_TRUE(readGreyImageFile(path("empty.png"), FeatureOptions(), &check).empty());
  EXPECT_EQ(check.problem, ImageProblem::kEmpty);
  EXPECT_TRUE(readGreyImageFile(path("absent.png"), FeatureOptions(), &check).empty());
  EXPECT_EQ(check.problem, ImageProblem::kFileRefused);
  test::writeBytes(path("truncated.jpg"), test::truncatedJpeg());
  EXPECT_TRUE(readGreyImageFile(path("truncated.jpg"), FeatureOptions(), &check).empty());
  EXPECT_EQ(check.problem, ImageProblem::kTruncated);
}

TEST(ImageDecoding, ADirectoryAFifoAndALinkToDevZeroAreRefusedQuickly) {
  const std::string dir = path("dir.png"), fifo = path("fifo.png"), zero = path("zero.png");
  ::rmdir(dir.c_str());
  std::remove(fifo.c_str());
  std::remove(zero.c_str());
  ASSERT_EQ(::mkdir(dir.c_str(), 0755), 0);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);  // nobody writes: a blocking open would hang
  ASSERT_EQ(::symlink("/dev/zero", zero.c_str()), 0);  // endless
  const long before = resetPeakKb();
  for (const std::string& p : {dir, fifo, zero}) {
    const auto t0 = std::chrono::steady_clock::now();
    ImageCheck check;
    EXPECT_TRUE(readGreyImageFile(p, FeatureOptions(), &check).empty());
    EXPECT_EQ(check.problem, ImageProblem::kFileRefused) << p << ": " << check.message();
    EXPECT_NE(check.detail.find(p), std::string::npos) << "the refusal names the file";
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  }
  if (before > 0) EXPECT_LT(peakKb() - before, 100 * 1024) << "kB over the baseline";
}

}  // namespace
}  // namespace bowg
