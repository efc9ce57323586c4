// Upstream features in message layout -> ImageFeatures: values kept
// exactly, inconsistent or unusable inputs refused naming the field.
#include "bowg/features/feature_arrays.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace bowg {
namespace {

FeatureArrays twoFeatures() {
  FeatureArrays a;
  a.image_width = 320;
  a.image_height = 240;
  a.x = {10.5f, 200.f};
  a.y = {20.f, 100.25f};
  a.size = {31.f, 12.f};
  a.angle = {-1.f, 90.f};
  a.response = {0.5f, 0.25f};
  a.octave = {0, 2};
  a.descriptors.assign(2 * 32, 0);
  a.descriptors[0] = 0x01;   // bit 0 of the first descriptor
  a.descriptors[32 + 31] = 0x80;  // bit 255 of the second
  return a;
}

std::string refusal(const FeatureArrays& a, const FeatureOptions& o = FeatureOptions()) {
  try {
    featuresFromArrays(a, o);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(FeatureArrays, ValuesAreKept) {
  const ImageFeatures f = featuresFromArrays(twoFeatures(), FeatureOptions());
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f.image_width, 320);
  EXPECT_EQ(f.keypoints[1].y, 100.25f);
  EXPECT_EQ(f.keypoints[1].octave, 2);
  EXPECT_EQ(f.descriptors[0].bits[0], 1u);
  EXPECT_EQ(f.descriptors[1].bits[3], 1ull << 63);
}

TEST(FeatureArrays, InconsistentArraysAreRefused) {
  FeatureArrays a = twoFeatures();
  a.octave.pop_back();
  EXPECT_NE(refusal(a).find("same length"), std::string::npos);
  a = twoFeatures();
  a.descriptors.pop_back();
  EXPECT_NE(refusal(a).find("descriptors has 63 bytes"), std::string::npos);
  a = twoFeatures();
  a.descriptors.resize(3 * 32);
  EXPECT_NE(refusal(a), "");
  a = twoFeatures();
  a.image_height = 0;
  EXPECT_NE(refusal(a).find("image_width and image_height"), std::string::npos);
}

TEST(FeatureArrays, UnusableValuesAndOversizeImagesAreRefused) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  FeatureArrays a = twoFeatures();
  a.y[0] = inf;
  EXPECT_NE(refusal(a).find("keypoint 0 has a non-finite position"), std::string::npos);
  a = twoFeatures();
  a.x[1] = -5e25f;  // far outside: the word-group grid's cell would overflow
  EXPECT_NE(refusal(a).find("keypoint 1 at"), std::string::npos) << refusal(a);
  a = twoFeatures();
  a.y[0] = 240.5f;
  EXPECT_NE(refusal(a).find("outside the 320 x 240 image"), std::string::npos) << refusal(a);
  a = twoFeatures();
  a.size[1] = nan;
  EXPECT_NE(refusal(a).find("keypoint 1"), std::string::npos);
  a = twoFeatures();
  a.size[1] = -2.f;
  EXPECT_NE(refusal(a), "");
  a = twoFeatures();
  a.angle[0] = nan;
  EXPECT_NE(refusal(a), "");
  a = twoFeatures();
  a.image_width = a.image_height = 30000;
  EXPECT_NE(refusal(a).find("max_image_pixels"), std::string::npos);
  FeatureOptions o;
  o.max_image_pixels = 320 * 240 - 1;
  EXPECT_NE(refusal(twoFeatures(), o).find("max_image_pixels 76799"), std::string::npos);
}

}  // namespace
}  // namespace bowg
