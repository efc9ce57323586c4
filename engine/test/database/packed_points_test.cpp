#include "bowg/database/packed_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "bowg/core/heap_bytes.h"
#include "bowg/features/feature_extractor.h"
#include "feature_test_images.h"

namespace bowg {
namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expectSameBits(const std::vector<ImagePoint>& given, const PackedPoints& packed) {
  ASSERT_EQ(packed.size(), given.size());
  const std::vector<ImagePoint> all = packed.unpack();
  for (std::size_t i = 0; i < given.size(); ++i) {
    EXPECT_TRUE(sameBits(packed[i].x, given[i].x) && sameBits(packed[i].y, given[i].y)) << i;
    EXPECT_TRUE(sameBits(all[i].x, given[i].x) && sameBits(all[i].y, given[i].y)) << i;
  }
}

TEST(PyramidLevelScale, IsOpenCvsFloatOfTheDoublePower) {
  EXPECT_EQ(pyramidLevelScale(1.2f, 0), 1.0f);
  EXPECT_EQ(pyramidLevelScale(1.2f, 1), 1.2f);
  // 1.2f = 1.2000000476837158; squared 1.4400001144409180, whose nearest
  // float is 1.44000005722045898 (1.44f is 1.44000005722045898 too).
  EXPECT_EQ(pyramidLevelScale(1.2f, 2), 1.44f);
  EXPECT_EQ(pyramidLevelScale(2.0f, 3), 8.0f);
}

TEST(PackedPoints, LevelGridPointsPackAndComeBackBitForBit) {
  // Level 1 of a 1.2 pyramid: 100 * 1.2f = 120.00000476837158, which rounds
  // to the float 120.00000762939453 (float spacing 2^-17 near 120), not 120.
  const float s1 = 1.2f;
  const ImagePoint level1{static_cast<float>(100) * s1, static_cast<float>(7) * s1};
  EXPECT_EQ(level1.x, 120.00000762939453f);
  const std::vector<ImagePoint> given = {{3.f, 5.f}, level1, {0.f, 0.f}, {16383.f, 8191.f}};
  const PackedPoints p(given, 1.2f);
  EXPECT_EQ(p.exactCount(), 0u);
  EXPECT_EQ(p.scaleFactor(), 1.2f);
  expectSameBits(given, p);
}

TEST(PackedPoints, OffGridPointsKeepTheirFloats) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<ImagePoint> given = {
      {0.5f, 3.f},        // no level's grid holds 0.5 (levels 0-15 of 1.2)
      {-2.f, 3.f},        // negative
      {-0.0f, 4.f},       // would come back as +0.0 from a code
      {nan, 1.f},         // not a number
      {3.f, 4.f},         // on the grid, between the others
      {123.25f, 9.75f}};  // sub-pixel
  const PackedPoints p(given, 1.2f);
  EXPECT_EQ(p.exactCount(), 5u);
  ASSERT_EQ(p.size(), given.size());
  // 6 codes then 5 x 2 float bit patterns in one block: 64 bytes, a 72-byte
  // request rounded up to an 80-byte malloc chunk.
  EXPECT_EQ(p.heapBytes(), 80u);
  EXPECT_TRUE(std::isnan(p[3].x));
  EXPECT_TRUE(std::signbit(p[2].x));
  for (std::size_t i : {0u, 1u, 2u, 4u, 5u}) {
    EXPECT_TRUE(sameBits(p[i].x, given[i].x) && sameBits(p[i].y, given[i].y)) << i;
  }
}

TEST(PackedPoints, WithoutAPyramidOnlyIntegerLevelZeroPointsPack) {
  // 120.00000762939453 is 100 x level 1's scale, but with no scale factor
  // there is no level 1; 16384 is beyond level 0's 14 bits.
  const std::vector<ImagePoint> given = {{120.00000762939453f, 2.f}, {16384.f, 0.f}, {7.f, 8.f}};
  for (float factor : {0.f, -1.2f, std::numeric_limits<float>::infinity()}) {
    const PackedPoints p(given, factor);
    EXPECT_EQ(p.scaleFactor(), 0.f);
    EXPECT_EQ(p.exactCount(), 2u);
    expectSameBits(given, p);
  }
}

TEST(PackedPoints, TheOctaveHintIsOnlyAHint) {
  // Hinted at the wrong level: found at its own.
  const ImagePoint level2{static_cast<float>(50) * pyramidLevelScale(1.2f, 2),
                          static_cast<float>(9) * pyramidLevelScale(1.2f, 2)};
  const std::vector<ImagePoint> given = {level2, {4.f, 4.f}};
  const PackedPoints p(given, 1.2f, {5, 99});
  EXPECT_EQ(p.exactCount(), 0u);
  expectSameBits(given, p);
}

TEST(PackedPoints, FourBytesAPointOnTheHeap) {
  // 500 codes: a request of 2,000 bytes, a 2,016-byte malloc chunk (2,000 +
  // 8, rounded up to 16); as floats 4,000 -> 4,016.
  std::vector<ImagePoint> given;
  for (int i = 0; i < 500; ++i)
    given.push_back({static_cast<float>(i), static_cast<float>(i % 400)});
  const PackedPoints p(given, 1.2f);
  EXPECT_EQ(p.exactCount(), 0u);
  EXPECT_EQ(p.heapBytes(), 2016u);
  EXPECT_EQ(vectorHeapBytes(std::vector<ImagePoint>(given)), 4016u);
  EXPECT_EQ(PackedPoints().heapBytes(), 0u);
}

TEST(PackedPoints, EveryOrbKeypointPacks) {
  // OpenCV's multi-scale ORB, as the pipe preset configures it: every
  // keypoint is an integer of its level times the level's scale.
  FeatureOptions o;
  o.detector = FeatureOptions::Detector::kOrb;
  o.descriptor = FeatureOptions::DescriptorType::kOrb;
  o.orb_fast_threshold = 10;
  const FeatureExtractor extractor(o);
  std::size_t upper_levels = 0;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const ImageFeatures f = extractor.extract(test::texturedImage(640, 480, 400, seed));
    ASSERT_GT(f.size(), 100u);
    EXPECT_EQ(f.pyramid_scale_factor, static_cast<float>(o.orb_scale_factor));
    const PackedPoints p = PackedPoints::fromKeypoints(f.keypoints, f.pyramid_scale_factor);
    EXPECT_EQ(p.exactCount(), 0u) << "seed " << seed;
    expectSameBits(imagePoints(f.keypoints), p);
    for (const Keypoint& k : f.keypoints) upper_levels += k.octave > 0 ? 1 : 0;
  }
  EXPECT_GT(upper_levels, 50u);  // the pyramid's levels were exercised
}

}  // namespace
}  // namespace bowg
