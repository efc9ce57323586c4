// detectGfttCorners against cv::goodFeaturesToTrack, which it must equal
// corner for corner and response for response: textured images, a
// checkerboard (responses tied in rows: the tie order), noise, a flat image,
// a mask, Harris, spacing below one pixel, no limit on the count, and the
// kept buffers meeting another image size.
#include "features/gftt_corners.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <string>

#include "feature_test_images.h"

namespace bowg {
namespace {

void expectSameAsOpenCv(const cv::Mat& image, const cv::Mat& mask, const GfttCornerOptions& o,
                        const std::string& what) {
  std::vector<cv::Point2f> want;
  std::vector<float> want_quality;
  cv::goodFeaturesToTrack(image, want, o.max_corners, o.quality_level, o.min_distance, mask,
                          want_quality, o.block_size, o.gradient_size, o.use_harris, o.harris_k);
  std::vector<cv::Point2f> got;
  std::vector<float> got_quality;
  detectGfttCorners(image, mask, o, got, got_quality);
  ASSERT_EQ(got.size(), want.size()) << what;
  ASSERT_EQ(got_quality.size(), want_quality.size()) << what;
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(got[i], want[i]) << what << ", corner " << i;
    ASSERT_EQ(got_quality[i], want_quality[i]) << what << ", corner " << i;
  }
}

GfttCornerOptions options(int max_corners, double min_distance, double quality, bool harris) {
  GfttCornerOptions o;
  o.max_corners = max_corners;
  o.min_distance = min_distance;
  o.quality_level = quality;
  o.use_harris = harris;
  return o;
}

TEST(GfttCorners, EqualsOpenCvOnTexturesForEveryLimitSpacingAndResponse) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const cv::Mat image = test::texturedImage(640, 480, 400, seed);
    for (int max_corners : {0, 50, 1000}) {
      for (double min_distance : {0.0, 0.5, 7.0, 10.0}) {
        for (double quality : {0.01, 0.1}) {
          for (bool harris : {false, true}) {
            expectSameAsOpenCv(
                image, cv::Mat(), options(max_corners, min_distance, quality, harris),
                "seed " + std::to_string(seed) + " max " + std::to_string(max_corners) +
                    " distance " + std::to_string(min_distance) + " quality " +
                    std::to_string(quality) + (harris ? " harris" : " min-eigen"));
          }
        }
      }
    }
  }
}

TEST(GfttCorners, EqualsOpenCvWhereResponsesTie) {
  // Every inner crossing of a checkerboard has the same response: OpenCV
  // orders ties by address, the later pixel first.
  const cv::Mat board = test::checkerboard(160, 120, 10);
  std::vector<cv::Point2f> corners;
  std::vector<float> quality;
  cv::goodFeaturesToTrack(board, corners, 0, 0.01, 0.0, cv::noArray(), quality, 3, 3, false, 0.04);
  ASSERT_GT(quality.size(), 100u);
  EXPECT_EQ(quality[0], quality[1]);  // the case under test: tied responses
  for (double min_distance : {0.0, 3.0, 10.0}) {
    expectSameAsOpenCv(board, cv::Mat(), options(0, min_distance, 0.01, false),
                       "checkerboard, distance " + std::to_string(min_distance));
    expectSameAsOpenCv(board, cv::Mat(), options(7, min_distance, 0.01, false),
                       "checkerboard, 7 corners, distance " + std::to_string(min_distance));
  }
}

TEST(GfttCorners, EqualsOpenCvOnNoiseAFlatImageAndUnderAMask) {
  cv::Mat noise(240, 320, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  expectSameAsOpenCv(noise, cv::Mat(), options(1000, 7.0, 0.01, false), "noise");

  const cv::Mat flat(120, 160, CV_8UC1, cv::Scalar(90));
  std::vector<cv::Point2f> corners{{1.f, 2.f}};
  std::vector<float> quality{3.f};
  detectGfttCorners(flat, cv::Mat(), options(100, 7.0, 0.01, false), corners, quality);
  EXPECT_TRUE(corners.empty());  // no response above zero: nothing, the old output cleared
  EXPECT_TRUE(quality.empty());
  expectSameAsOpenCv(flat, cv::Mat(), options(100, 7.0, 0.01, false), "flat");

  // A disc of usable pixels, as a pipe camera's mask: corners outside it
  // are not candidates and the strongest response is taken inside it.
  const cv::Mat image = test::texturedImage(640, 480, 400, 4);
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(0));
  cv::circle(mask, cv::Point(320, 240), 200, cv::Scalar(255), cv::FILLED);
  expectSameAsOpenCv(image, mask, options(1000, 7.0, 0.01, false), "masked");
}

TEST(GfttCorners, TheKeptBuffersFollowTheImageSize) {
  // The same thread's buffers meet a large, a small and again a large image.
  const cv::Mat large = test::texturedImage(640, 480, 400, 5);
  const cv::Mat small = test::texturedImage(320, 240, 150, 6);
  const GfttCornerOptions o = options(1000, 7.0, 0.01, false);
  expectSameAsOpenCv(large, cv::Mat(), o, "640x480");
  expectSameAsOpenCv(small, cv::Mat(), o, "320x240 after 640x480");
  expectSameAsOpenCv(large, cv::Mat(), o, "640x480 after 320x240");
}

}  // namespace
}  // namespace bowg
