// FeatureExtractor: options validation, bad input, GFTT and multi-scale ORB
// extraction on synthetic images, masks, border dropping, roll robustness.
#include "bowg/features/feature_extractor.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "bowg/core/errors.h"
#include "bowg/features/brief_descriptor.h"
#include "bowg/features/brief_pattern.h"
#include "bowg/features/descriptor_conversion.h"
#include "bowg/features/orb_descriptor.h"
#include "core/special_files.h"
#include "encoded_test_images.h"
#include "feature_test_images.h"

namespace bowg {
namespace {

std::string outPath(const std::string& name) {
  return std::string(BOWG_TEST_OUTPUT_DIR) + "/" + name;
}

std::string vinsPattern() {
  return std::string(BOWG_SHARED_DATA_DIR) + "/vocabularies/brief_pattern.yml";
}

// A small self-made pattern (radius 12) for tests that must not need shared data.
std::string writeTestPattern() {
  const std::string path = outPath("feature_test_pattern.yml");
  cv::RNG rng(13);
  std::vector<int> v[4];
  for (auto& s : v) {
    for (int i = 0; i < 256; ++i) s.push_back(rng.uniform(-12, 13));
  }
  cv::FileStorage fs(path, cv::FileStorage::WRITE);
  fs << "x1" << v[0] << "y1" << v[1] << "x2" << v[2] << "y2" << v[3];
  return path;
}

void expectInvalid(const std::function<void(FeatureOptions&)>& change, const std::string& field) {
  FeatureOptions o;
  change(o);
  try {
    o.validate();
    FAIL() << "no exception for " << field;
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("features." + field), std::string::npos) << e.what();
  }
}

TEST(FeatureOptions, DefaultsAreValid) { EXPECT_NO_THROW(FeatureOptions().validate()); }

TEST(FeatureOptions, EachInvalidValueNamesItsField) {
  const double nan = std::nan("");
  expectInvalid([](FeatureOptions& o) { o.gftt_max_corners = 0; }, "gftt_max_corners");
  expectInvalid([](FeatureOptions& o) { o.gftt_quality_level = 0.0; }, "gftt_quality_level");
  expectInvalid([](FeatureOptions& o) { o.gftt_quality_level = 1.5; }, "gftt_quality_level");
  expectInvalid([&](FeatureOptions& o) { o.gftt_quality_level = nan; }, "gftt_quality_level");
  expectInvalid([](FeatureOptions& o) { o.gftt_min_distance = -1.0; }, "gftt_min_distance");
  expectInvalid([&](FeatureOptions& o) { o.gftt_min_distance = nan; }, "gftt_min_distance");
  expectInvalid([](FeatureOptions& o) { o.gftt_block_size = 0; }, "gftt_block_size");
  expectInvalid([](FeatureOptions& o) { o.gftt_keypoint_size = 0.0; }, "gftt_keypoint_size");
  expectInvalid([](FeatureOptions& o) { o.gftt_keypoint_size = INFINITY; }, "gftt_keypoint_size");
  expectInvalid([](FeatureOptions& o) { o.gftt_levels = 0; }, "gftt_levels");
  expectInvalid([](FeatureOptions& o) { o.gftt_levels = 33; }, "gftt_levels");
  expectInvalid(
      [](FeatureOptions& o) {
        o.gftt_levels = 2;
        o.descriptor = FeatureOptions::DescriptorType::kBrief;
        o.brief_pattern_path = "pattern.yml";
      },
      "gftt_levels");
  expectInvalid([](FeatureOptions& o) { o.orb_max_features = 0; }, "orb_max_features");
  expectInvalid([](FeatureOptions& o) { o.orb_scale_factor = 1.0; }, "orb_scale_factor");
  expectInvalid([&](FeatureOptions& o) { o.orb_scale_factor = nan; }, "orb_scale_factor");
  expectInvalid([](FeatureOptions& o) { o.orb_levels = 0; }, "orb_levels");
  expectInvalid([](FeatureOptions& o) { o.orb_fast_threshold = 0; }, "orb_fast_threshold");
  expectInvalid([](FeatureOptions& o) { o.orb_fast_threshold = 255; }, "orb_fast_threshold");
  expectInvalid([](FeatureOptions& o) { o.max_image_pixels = 0; }, "max_image_pixels");
  expectInvalid([](FeatureOptions& o) { o.descriptor = FeatureOptions::DescriptorType::kBrief; },
                "brief_pattern_path");
  expectInvalid([](FeatureOptions& o) { o.detector = static_cast<FeatureOptions::Detector>(7); },
                "detector");
  expectInvalid(
      [](FeatureOptions& o) { o.descriptor = static_cast<FeatureOptions::DescriptorType>(7); },
      "descriptor");
  // The constructor validates too.
  FeatureOptions o;
  o.gftt_max_corners = -3;
  EXPECT_THROW(FeatureExtractor{o}, InvalidParameter);
}

template <typename E>
void expectThrowContaining(const std::function<void()>& f, const std::string& text) {
  try {
    f();
    FAIL() << "no exception, expected one mentioning '" << text << "'";
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(FeatureExtractor, BadImagesAreRejectedWithTheProblem) {
  const FeatureExtractor fx{FeatureOptions()};
  expectThrowContaining<std::invalid_argument>([&] { fx.extract(cv::Mat()); }, "empty");
  expectThrowContaining<std::invalid_argument>([&] { fx.extract(cv::Mat(50, 50, CV_8UC3)); },
                                               "single-channel");
  expectThrowContaining<std::invalid_argument>([&] { fx.extract(cv::Mat(50, 50, CV_16UC1)); },
                                               "8-bit");
  expectThrowContaining<std::invalid_argument>([&] { fx.extract(cv::Mat(50, 50, CV_32FC1)); },
                                               "8-bit");
}

TEST(FeatureExtractor, ImagesAboveMaxImagePixelsAreRejected) {
  FeatureOptions o;
  o.max_image_pixels = 64 * 48;
  const FeatureExtractor fx{o};
  EXPECT_NO_THROW(fx.extract(cv::Mat(48, 64, CV_8UC1, cv::Scalar(0))));  // exactly the limit
  expectThrowContaining<std::invalid_argument>(
      [&] { fx.extract(cv::Mat(49, 64, CV_8UC1, cv::Scalar(0))); },
      "64 x 49 = 3136 pixels, more than max_image_pixels 3072");
  // The default: 4096 x 4096.
  EXPECT_EQ(imageSizeProblem(4096, 4096, FeatureOptions()), "");
  EXPECT_EQ(imageSizeProblem(4097, 4096, FeatureOptions()),
            "4097 x 4096 = 16781312 pixels, more than max_image_pixels 16777216");
}

// Every detector / descriptor combination on tiny and flat images: no
// features, no crash.
TEST(FeatureExtractor, TinyAndFlatImagesGiveNoFeatures) {
  const std::string pattern = writeTestPattern();
  for (auto det : {FeatureOptions::Detector::kGftt, FeatureOptions::Detector::kOrb}) {
    for (auto desc :
         {FeatureOptions::DescriptorType::kOrb, FeatureOptions::DescriptorType::kBrief}) {
      for (bool oriented : {true, false}) {
        FeatureOptions o;
        o.detector = det;
        o.descriptor = desc;
        o.compute_orientation = oriented;
        o.brief_pattern_path = pattern;
        const FeatureExtractor fx(o);
        for (const cv::Size size : {cv::Size(10, 10), cv::Size(1, 1), cv::Size(40, 30)}) {
          const ImageFeatures f = fx.extract(test::checkerboard(size.width, size.height, 3));
          EXPECT_TRUE(f.empty()) << size;
          EXPECT_TRUE(f.descriptors.empty());
          EXPECT_EQ(f.image_width, size.width);
        }
        EXPECT_TRUE(fx.extract(cv::Mat(200, 200, CV_8UC1, cv::Scalar(77))).empty());
      }
    }
  }
}

// Checks shared by every extraction: alignment, fields, border.
void checkFeatures(const ImageFeatures& f, const cv::Mat& img, int radius, bool oriented) {
  ASSERT_EQ(f.keypoints.size(), f.descriptors.size());
  EXPECT_EQ(f.image_width, img.cols);
  EXPECT_EQ(f.image_height, img.rows);
  for (const Keypoint& k : f.keypoints) {
    const double scale = std::pow(1.2, k.octave);
    EXPECT_GE(k.x / scale, radius);
    EXPECT_GE(k.y / scale, radius);
    EXPECT_LE(k.x / scale, cvRound(img.cols / scale) - 1 - radius);
    EXPECT_LE(k.y / scale, cvRound(img.rows / scale) - 1 - radius);
    if (oriented) {
      EXPECT_GE(k.angle, 0.f);
      EXPECT_LT(k.angle, 360.f);
    } else {
      EXPECT_EQ(k.angle, -1.f);
    }
  }
}

TEST(FeatureExtractor, GfttOnACheckerboard) {
  // 320x240, 20 px squares: 15 x 11 inner corners; those at least 22 px from
  // the border (oriented ORB) are x = 40..280, y = 40..200: 13 x 9 = 117.
  const cv::Mat img = test::checkerboard(320, 240, 20);
  FeatureOptions o;
  o.gftt_keypoint_size = 25.0;
  const ImageFeatures f = FeatureExtractor(o).extract(img);
  checkFeatures(f, img, kOrbSteeredRadius, true);
  EXPECT_GE(f.size(), 100u);
  EXPECT_LE(f.size(), 130u);
  for (const Keypoint& k : f.keypoints) {
    EXPECT_EQ(k.size, 25.f);
    EXPECT_EQ(k.octave, 0);
    EXPECT_GT(k.response, 0.f);
  }
}

// gftt_levels 3: corners on three levels of the 1.2 pyramid, each level at
// most ORB's share of the 1,000 corners (by hand: 1000 (1 - 1/1.2) /
// (1 - 1.2^-3) = 395.6 -> 396, then 396 / 1.2 = 329.7 -> 330, the rest 274),
// each reported as ORB reports its keypoints: level-0 position, size 25 x
// 1.2^level, the level as the octave.
TEST(FeatureExtractor, GfttOnPyramidLevels) {
  const cv::Mat img = test::checkerboard(320, 240, 20);
  FeatureOptions o;
  o.gftt_keypoint_size = 25.0;
  o.gftt_max_corners = 1000;
  o.gftt_levels = 3;
  const ImageFeatures f = FeatureExtractor(o).extract(img);
  checkFeatures(f, img, kOrbSteeredRadius, true);
  EXPECT_FLOAT_EQ(f.pyramid_scale_factor, 1.2f);
  int per_octave[3] = {0, 0, 0};
  for (const Keypoint& k : f.keypoints) {
    ASSERT_GE(k.octave, 0);
    ASSERT_LT(k.octave, 3);
    ++per_octave[k.octave];
    EXPECT_FLOAT_EQ(k.size, static_cast<float>(25.0 * std::pow(1.2, k.octave)));
    // A corner of the board wherever it was found: within 2.5 level pixels
    // of a multiple of 20 px in the image (GFTT gives whole level pixels; a
    // board corner of level 2 lies between them, 240 / 1.44 = 166.7, and
    // the shrunk board's blur moves the strongest response by a pixel).
    const double dx = std::remainder(k.x, 20.0), dy = std::remainder(k.y, 20.0);
    EXPECT_LE(std::hypot(dx, dy), 2.5 * std::pow(1.2, k.octave)) << k.x << ", " << k.y;
  }
  EXPECT_GE(per_octave[0], 100);
  EXPECT_LE(per_octave[0], 396);
  EXPECT_GT(per_octave[1], 50);
  EXPECT_LE(per_octave[1], 330);
  EXPECT_GT(per_octave[2], 30);
  EXPECT_LE(per_octave[2], 274);
  // One level is the single-scale extraction.
  o.gftt_levels = 1;
  const ImageFeatures single = FeatureExtractor(o).extract(img);
  FeatureOptions before;
  before.gftt_keypoint_size = 25.0;
  before.gftt_max_corners = 1000;
  const ImageFeatures want = FeatureExtractor(before).extract(img);
  ASSERT_EQ(single.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(single.keypoints[i].x, want.keypoints[i].x);
    EXPECT_EQ(single.descriptors[i], want.descriptors[i]);
  }
}

TEST(FeatureExtractor, GfttDropsKeypointsWhosePatchLeavesTheImage) {
  // A textured image: GFTT finds corners near the border too; only those
  // within the patch radius are dropped.
  const cv::Mat img = test::texturedImage(320, 240, 200, 31);
  FeatureOptions o;
  const ImageFeatures oriented = FeatureExtractor(o).extract(img);
  checkFeatures(oriented, img, kOrbSteeredRadius, true);
  o.compute_orientation = false;
  const ImageFeatures upright = FeatureExtractor(o).extract(img);
  checkFeatures(upright, img, kOrbUprightRadius, false);
  // Upright needs less border, so it keeps more (and at least one corner in
  // the 16..22 px band).
  EXPECT_GT(upright.size(), oriented.size());
  EXPECT_GT(oriented.size(), 150u);
}

TEST(FeatureExtractor, GfttOrbDescriptorsEqualOrbOnTheSameKeypoints) {
  const cv::Mat img = test::texturedImage(320, 240, 200, 32);
  const ImageFeatures f = FeatureExtractor(FeatureOptions()).extract(img);
  ASSERT_FALSE(f.empty());
  std::vector<cv::KeyPoint> kps;
  for (const Keypoint& k : f.keypoints) kps.emplace_back(k.x, k.y, 31.f, k.angle, 0.f, 0);
  cv::Mat d;
  cv::ORB::create(500, 1.2f, 1, 22)->compute(img, kps, d);
  ASSERT_EQ(kps.size(), f.size());
  const std::vector<Descriptor> want = descriptorsFromMat(d);
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(f.descriptors[i], want[i]) << i;
}

TEST(FeatureExtractor, MultiScaleOrbMatchesOpenCv) {
  const cv::Mat img = test::texturedImage(640, 480, 400, 33);
  FeatureOptions o;
  o.detector = FeatureOptions::Detector::kOrb;
  o.orb_max_features = 400;
  const ImageFeatures f = FeatureExtractor(o).extract(img);
  checkFeatures(f, img, kOrbSteeredRadius, true);
  EXPECT_GT(f.size(), 300u);
  EXPECT_LE(f.size(), 400u);
  // The same keypoints and descriptors as cv::ORB with the same parameters.
  std::vector<cv::KeyPoint> kps;
  cv::Mat d;
  cv::ORB::create(400, 1.2f, 8, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, 20)
      ->detectAndCompute(img, cv::noArray(), kps, d);
  ASSERT_EQ(kps.size(), f.size());
  const std::vector<Descriptor> want = descriptorsFromMat(d);
  int max_octave = 0;
  for (std::size_t i = 0; i < kps.size(); ++i) {
    EXPECT_EQ(f.keypoints[i].x, kps[i].pt.x);
    EXPECT_EQ(f.keypoints[i].octave, kps[i].octave);
    EXPECT_EQ(f.keypoints[i].size, kps[i].size);
    EXPECT_EQ(f.keypoints[i].angle, kps[i].angle);
    EXPECT_EQ(f.keypoints[i].response, kps[i].response);
    EXPECT_EQ(f.descriptors[i], want[i]) << i;
    max_octave = std::max(max_octave, kps[i].octave);
  }
  EXPECT_GE(max_octave, 3);
}

TEST(FeatureExtractor, ExtractionIsDeterministic) {
  const cv::Mat img = test::texturedImage(320, 240, 150, 34);
  for (auto det : {FeatureOptions::Detector::kGftt, FeatureOptions::Detector::kOrb}) {
    FeatureOptions o;
    o.detector = det;
    const FeatureExtractor fx(o);
    const ImageFeatures a = fx.extract(img), b = fx.extract(img);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a.keypoints[i].x, b.keypoints[i].x);
      EXPECT_EQ(a.descriptors[i], b.descriptors[i]);
    }
  }
}

// Mean Hamming distance between the descriptors of corners found again at
// their rotated position after a 90-degree clockwise rotation (a robot roll).
double meanDistanceAfterRotation(const FeatureExtractor& fx, const cv::Mat& img, int* matched) {
  cv::Mat rot;
  cv::rotate(img, rot, cv::ROTATE_90_CLOCKWISE);
  const ImageFeatures a = fx.extract(img), b = fx.extract(rot);
  double sum = 0;
  *matched = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const float qx = img.rows - 1 - a.keypoints[i].y, qy = a.keypoints[i].x;
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (std::fabs(b.keypoints[j].x - qx) < 0.5f && std::fabs(b.keypoints[j].y - qy) < 0.5f) {
        sum += hammingDistance(a.descriptors[i], b.descriptors[j]);
        ++*matched;
        break;
      }
    }
  }
  return *matched ? sum / *matched : 0.0;
}

TEST(FeatureExtractor, OrientedDescriptorsSurviveRollUprightDoNot) {
  const cv::Mat img = test::texturedImage(320, 240, 200, 35);
  for (auto desc : {FeatureOptions::DescriptorType::kOrb, FeatureOptions::DescriptorType::kBrief}) {
    FeatureOptions o;
    o.descriptor = desc;
    o.brief_pattern_path = writeTestPattern();
    int n_or = 0, n_up = 0;
    const double d_or = meanDistanceAfterRotation(FeatureExtractor(o), img, &n_or);
    o.compute_orientation = false;
    const double d_up = meanDistanceAfterRotation(FeatureExtractor(o), img, &n_up);
    std::cout << (desc == FeatureOptions::DescriptorType::kOrb ? "ORB" : "BRIEF")
              << " mean Hamming after 90 deg roll: oriented " << d_or << " (" << n_or
              << " corners), upright " << d_up << " (" << n_up << ")\n";
    EXPECT_GT(n_or, 100);
    EXPECT_GT(n_up, 100);
    EXPECT_LT(d_or, 10.0);
    EXPECT_GT(d_up, 60.0);
  }
}

TEST(FeatureExtractor, BriefEqualsDVisionStyleComputation) {
  const std::string pattern_path =
      std::ifstream(vinsPattern()).good() ? vinsPattern() : writeTestPattern();
  const cv::Mat img = test::texturedImage(320, 240, 200, 36);
  FeatureOptions o;
  o.descriptor = FeatureOptions::DescriptorType::kBrief;
  o.compute_orientation = false;  // VINS compatibility
  o.brief_pattern_path = pattern_path;
  const ImageFeatures f = FeatureExtractor(o).extract(img);
  const std::vector<cv::Vec4i> pattern = loadBriefPattern(pattern_path);
  checkFeatures(f, img, briefPatternRadius(pattern, false), false);
  ASSERT_GT(f.size(), 100u);
  std::vector<cv::KeyPoint> kps;
  for (const Keypoint& k : f.keypoints) kps.emplace_back(k.x, k.y, k.size);
  const auto want = computeBriefDescriptors(smoothForBrief(img), pattern, kps, false);
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(f.descriptors[i], want[i]);
}

TEST(FeatureExtractor, MaskExcludesBlankedPixels) {
  const cv::Mat img = test::texturedImage(320, 240, 200, 37);
  cv::Mat mask(240, 320, CV_8UC1, cv::Scalar(255));
  mask.colRange(0, 160).setTo(0);
  const std::string path = outPath("feature_mask_left.png");
  ASSERT_TRUE(cv::imwrite(path, mask));
  for (auto det : {FeatureOptions::Detector::kGftt, FeatureOptions::Detector::kOrb}) {
    FeatureOptions o;
    o.detector = det;
    const std::size_t unmasked = FeatureExtractor(o).extract(img).size();
    o.mask_path = path;
    const ImageFeatures f = FeatureExtractor(o).extract(img);
    EXPECT_GT(f.size(), 20u);
    EXPECT_LT(f.size(), unmasked);
    for (const Keypoint& k : f.keypoints) EXPECT_GE(k.x, 159.f);
  }
}

TEST(FeatureExtractor, ColourMaskCountsAnyNonZeroChannel) {
  const cv::Mat img = test::texturedImage(320, 240, 200, 37);
  cv::Mat mask(240, 320, CV_8UC3, cv::Scalar(0, 0, 0));
  mask.rowRange(120, 240).setTo(cv::Scalar(0, 0, 1));  // only red = 1 (BGR)
  const std::string path = outPath("feature_mask_colour.png");
  ASSERT_TRUE(cv::imwrite(path, mask));
  FeatureOptions o;
  o.mask_path = path;
  const ImageFeatures f = FeatureExtractor(o).extract(img);
  EXPECT_GT(f.size(), 20u);
  for (const Keypoint& k : f.keypoints) EXPECT_GE(k.y, 120.f);
}

TEST(FeatureExtractor, BadMaskAndPatternFilesNameThePath) {
  FeatureOptions o;
  o.mask_path = outPath("no_such_mask.png");
  expectThrowContaining<IoError>([&] { FeatureExtractor{o}; }, o.mask_path);
  o.mask_path = outPath("corrupt_mask.png");
  std::ofstream(o.mask_path) << "not a png";
  expectThrowContaining<FormatError>([&] { FeatureExtractor{o}; }, o.mask_path);
  o.mask_path = outPath("mask_cut.jpg");  // a JPEG cut short: refused from its header
  test::writeBytes(o.mask_path, test::truncatedJpeg());
  expectThrowContaining<FormatError>([&] { FeatureExtractor{o}; }, "truncated");
  o.mask_path = outPath("mask_dir.png");  // a directory: refused without reading
  ::mkdir(o.mask_path.c_str(), 0755);
  expectThrowContaining<IoError>([&] { FeatureExtractor{o}; }, o.mask_path);
  o.mask_path = outPath("mask_16bit.png");
  ASSERT_TRUE(cv::imwrite(o.mask_path, cv::Mat(240, 320, CV_16UC1, cv::Scalar(1000))));
  expectThrowContaining<FormatError>([&] { FeatureExtractor{o}; }, o.mask_path);

  // Size mismatch: found at extraction.
  o.mask_path = outPath("mask_small.png");
  ASSERT_TRUE(cv::imwrite(o.mask_path, cv::Mat(100, 100, CV_8UC1, cv::Scalar(255))));
  const FeatureExtractor fx(o);
  expectThrowContaining<std::invalid_argument>(
      [&] { fx.extract(test::texturedImage(320, 240, 10, 1)); }, "mask");

  FeatureOptions b;
  b.descriptor = FeatureOptions::DescriptorType::kBrief;
  b.brief_pattern_path = outPath("no_such_pattern.yml");
  expectThrowContaining<IoError>([&] { FeatureExtractor{b}; }, b.brief_pattern_path);
}

TEST(FeatureExtractor, SpecialMaskFilesAreRefusedFast) {
  const auto files = testing::makeSpecialFiles(std::string(BOWG_TEST_OUTPUT_DIR) + "/mask", ".png",
                                               3ull << 30, "more than the limit");
  const auto load = [](const std::string& p) {
    FeatureOptions o;
    o.mask_path = p;
    FeatureExtractor{o};
  };
  testing::expectSpecialFilesRefused(files, load);
  testing::expectRefusedFast(outPath("absent_mask.png"), "No such file or directory", load);
}

}  // namespace
}  // namespace bowg
