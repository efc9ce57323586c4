// GFTT on real 320x240 sewer CCTV frames (shared data, see
// /work/shared/data/README.md): a reasonable number of corners per frame, and
// a mask blanking the burned-in text overlay keeps features off it.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "bowg/features/feature_extractor.h"

namespace bowg {
namespace {

// Burned-in overlay: text in the top 32 and the bottom 40 rows.
const int kOverlayTop = 32;
const int kOverlayBottom = 40;

std::vector<cv::Mat> loadFrames(std::string* dir) {
  *dir = std::string(BOWG_SHARED_DATA_DIR) + "/sewer_cctv/left";
  std::vector<cv::String> files;
  if (std::ifstream(*dir + "/1_16_left_108100.png").good()) cv::glob(*dir + "/*.png", files);
  std::sort(files.begin(), files.end());
  std::vector<cv::Mat> frames;
  for (const cv::String& f : files) frames.push_back(cv::imread(f, cv::IMREAD_GRAYSCALE));
  return frames;
}

TEST(FeatureSewer, GfttFindsAReasonableNumberOfCorners) {
  std::string dir;
  const std::vector<cv::Mat> frames = loadFrames(&dir);
  if (frames.empty()) GTEST_SKIP() << "shared sewer frames absent: " << dir;
  const FeatureExtractor fx{FeatureOptions()};
  std::vector<std::size_t> counts;
  for (const cv::Mat& f : frames) {
    ASSERT_EQ(f.size(), cv::Size(320, 240));
    counts.push_back(fx.extract(f).size());
  }
  std::sort(counts.begin(), counts.end());
  const std::size_t median = counts[counts.size() / 2];
  std::cout << frames.size() << " sewer frames, GFTT features per frame: min " << counts.front()
            << ", median " << median << ", max " << counts.back() << "\n";
  // Measured: min 9, median 61, max 221. The strong corners of the text
  // overlay set GFTT's relative quality threshold (0.01 x the best corner),
  // which suppresses the weaker wall corners: see the masked test below.
  EXPECT_GE(counts.front(), 5u);
  EXPECT_GE(median, 40u);
  EXPECT_LE(counts.back(), 500u);
}

TEST(FeatureSewer, MaskKeepsFeaturesOffTheTextOverlay) {
  std::string dir;
  const std::vector<cv::Mat> frames = loadFrames(&dir);
  if (frames.empty()) GTEST_SKIP() << "shared sewer frames absent: " << dir;
  cv::Mat mask(240, 320, CV_8UC1, cv::Scalar(255));
  mask.rowRange(0, kOverlayTop).setTo(0);
  mask.rowRange(240 - kOverlayBottom, 240).setTo(0);
  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/sewer_overlay_mask.png";
  ASSERT_TRUE(cv::imwrite(path, mask));
  FeatureOptions o;
  const FeatureExtractor plain(o);
  o.mask_path = path;
  const FeatureExtractor masked(o);
  std::size_t on_overlay_plain = 0;
  std::vector<std::size_t> plain_counts, masked_counts;
  for (const cv::Mat& frame : frames) {
    const ImageFeatures p = plain.extract(frame);
    for (const Keypoint& k : p.keypoints) {
      if (k.y < kOverlayTop || k.y >= 240 - kOverlayBottom) ++on_overlay_plain;
    }
    const ImageFeatures f = masked.extract(frame);
    for (const Keypoint& k : f.keypoints) {
      EXPECT_GE(k.y, kOverlayTop);
      EXPECT_LT(k.y, 240 - kOverlayBottom);
    }
    plain_counts.push_back(p.size());
    masked_counts.push_back(f.size());
  }
  std::sort(plain_counts.begin(), plain_counts.end());
  std::sort(masked_counts.begin(), masked_counts.end());
  const std::size_t plain_median = plain_counts[plain_counts.size() / 2];
  const std::size_t masked_median = masked_counts[masked_counts.size() / 2];
  std::cout << "masked: min " << masked_counts.front() << ", median " << masked_median << ", max "
            << masked_counts.back() << "; unmasked features on the overlay: " << on_overlay_plain
            << "\n";
  // Without the mask the overlay text attracts corners...
  EXPECT_GT(on_overlay_plain, 0u);
  // ...and masking it lets the wall corners through (measured: median 122
  // against 61 unmasked).
  EXPECT_GE(masked_counts.front(), 20u);
  EXPECT_GE(masked_median, 100u);
  EXPECT_GT(masked_median, plain_median);
}

}  // namespace
}  // namespace bowg
