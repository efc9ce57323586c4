// Word groups (paper Sec. III-A "Word Group Definition"), with values worked
// out by hand in the comments. The table, eq. 1 and eq. 3:
// word_group_scores_test.cpp.
#include "bowg/scoring/word_groups.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>

namespace bowg {
namespace {

Keypoint kp(float x, float y, float size) {
  Keypoint k;
  k.x = x;
  k.y = y;
  k.size = size;
  return k;
}

// Four keypoints:
//   k0 (0, 0)     size 5   word 10
//   k1 (3, 0)     size 2   word 20
//   k2 (0, 4)     size 5   word 30
//   k3 (100, 100) size 10  word 40
// Distances: d01 = 3, d02 = 4, d12 = 5, everything to k3 > 100.
std::vector<Keypoint> fourKeypoints() {
  return {kp(0, 0, 5), kp(3, 0, 2), kp(0, 4, 5), kp(100, 100, 10)};
}

// O(n^2) reference of the word-group definition, to check the grid search.
GroupVector bruteForceGroups(const std::vector<Keypoint>& kps, const std::vector<WordId>& words,
                             double radius_scale) {
  std::map<WordId, double> g;
  for (std::size_t i = 0; i < kps.size(); ++i) {
    const double r = radius_scale * kps[i].size;
    int n = 0;
    for (std::size_t j = 0; j < kps.size(); ++j) {
      if (j == i) continue;
      const double dx = static_cast<double>(kps[j].x) - kps[i].x;
      const double dy = static_cast<double>(kps[j].y) - kps[i].y;
      if (dx * dx + dy * dy < r * r) ++n;
    }
    if (n > 0) g[words[i]] += n;
  }
  return GroupVector(g.begin(), g.end());
}

TEST(WordGroups, FourKeypointsByHand) {
  // k0 (r = 5): k1 (3 < 5) and k2 (4 < 5) -> group 10 has weight 2.
  // k1 (r = 2): k0 at 3 and k2 at 5 are both >= 2 -> no group 20, although
  //             k1 is in k0's group (the radius is the centre's size).
  // k2 (r = 5): k0 (4 < 5); k1 at exactly 5 is not strictly closer -> 1.
  // k3: isolated -> dropped.
  const GroupVector g = buildWordGroups(fourKeypoints(), {10, 20, 30, 40}, WordGroupOptions());
  const GroupVector expected{{10, 2.0}, {30, 1.0}};
  EXPECT_EQ(g, expected);
}

TEST(WordGroups, MembershipIsAsymmetricWhenSizesDiffer) {
  // Two points 3 px apart: the large one (r = 5) holds the small one (r = 2)
  // in its group, not vice versa.
  const GroupVector g = buildWordGroups({kp(0, 0, 5), kp(3, 0, 2)}, {1, 2}, WordGroupOptions());
  const GroupVector expected{{1, 1.0}};
  EXPECT_EQ(g, expected);
}

TEST(WordGroups, SameWordTwiceAddsUp) {
  // k0 and k2 share word 7: weights 2 (k0) + 1 (k2) = 3 in the one group 7.
  const GroupVector g = buildWordGroups(fourKeypoints(), {7, 20, 7, 40}, WordGroupOptions());
  const GroupVector expected{{7, 3.0}};
  EXPECT_EQ(g, expected);
}

TEST(WordGroups, RadiusScaleMultipliesTheSize) {
  // radius_scale 2: k0 r = 10 -> k1, k2 (2); k1 r = 4 -> k0 at 3 (1), k2 at 5
  // no; k2 r = 10 -> k0, k1 at 5 (2); k3 r = 20 still isolated.
  WordGroupOptions o;
  o.radius_scale = 2.0;
  const GroupVector g = buildWordGroups(fourKeypoints(), {10, 20, 30, 40}, o);
  const GroupVector expected{{10, 2.0}, {20, 1.0}, {30, 2.0}};
  EXPECT_EQ(g, expected);
}

TEST(WordGroups, OutputSortedById) {
  // Same geometry as FourKeypointsByHand with decreasing word ids.
  const GroupVector g = buildWordGroups(fourKeypoints(), {90, 80, 70, 60}, WordGroupOptions());
  const GroupVector expected{{70, 1.0}, {90, 2.0}};
  EXPECT_EQ(g, expected);
}

TEST(WordGroups, IsolatedAndDegenerateInputsGiveNoGroups) {
  EXPECT_TRUE(buildWordGroups({}, {}, WordGroupOptions()).empty());
  EXPECT_TRUE(buildWordGroups({kp(1, 1, 10)}, {3}, WordGroupOptions()).empty());
  // Size 0: nothing is strictly closer than 0, even a point at the same spot.
  EXPECT_TRUE(buildWordGroups({kp(1, 1, 0), kp(1, 1, 0)}, {3, 4}, WordGroupOptions()).empty());
}

TEST(WordGroups, CoincidentPointsAreNeighbours) {
  // Distance 0 < 1 both ways.
  const GroupVector g = buildWordGroups({kp(5, 5, 1), kp(5, 5, 1)}, {3, 4}, WordGroupOptions());
  const GroupVector expected{{3, 1.0}, {4, 1.0}};
  EXPECT_EQ(g, expected);
}

TEST(WordGroups, MismatchedSizesThrow) {
  EXPECT_THROW(buildWordGroups(fourKeypoints(), {1, 2, 3}, WordGroupOptions()),
               std::invalid_argument);
}

TEST(WordGroups, BadKeypointsThrow) {
  const WordGroupOptions o;
  EXPECT_THROW(buildWordGroups({kp(0, 0, -1), kp(1, 0, 2)}, {1, 2}, o), std::invalid_argument);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(buildWordGroups({kp(nan, 0, 1), kp(1, 0, 2)}, {1, 2}, o), std::invalid_argument);
  EXPECT_THROW(buildWordGroups({kp(0, 0, nan), kp(1, 0, 2)}, {1, 2}, o), std::invalid_argument);
  WordGroupOptions bad;
  bad.radius_scale = 0.0;
  EXPECT_THROW(buildWordGroups(fourKeypoints(), {1, 2, 3, 4}, bad), std::invalid_argument);
}

// A keypoint of a huge (finite) size, from a bad upstream feature, reaches
// far past the grid of the others' small cells: its reach must be clamped
// to the grid before it becomes a cell number (which would not fit an
// integer: undefined behaviour, caught by the UBSan build of the tests).
TEST(WordGroups, AHugeNeighbourhoodIsClampedToTheGrid) {
  const std::vector<Keypoint> kps{kp(0, 0, 4), kp(1, 0, 4), kp(2, 1, 4), kp(3, 3, 1e26f),
                                  kp(300, 200, 4)};
  const std::vector<WordId> words{1, 2, 3, 4, 5};
  const GroupVector g = buildWordGroups(kps, words, WordGroupOptions());
  EXPECT_EQ(g, bruteForceGroups(kps, words, 1.0));
}

TEST(WordGroups, GridSearchMatchesAllPairs) {
  // 600 keypoints of mixed sizes in a 640x480 image, a few words repeated.
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> ux(0.f, 640.f), uy(0.f, 480.f), us(1.f, 45.f);
  std::uniform_int_distribution<WordId> uw(0, 150);
  std::vector<Keypoint> kps;
  std::vector<WordId> words;
  for (int i = 0; i < 600; ++i) {
    kps.push_back(kp(ux(rng), uy(rng), us(rng)));
    words.push_back(uw(rng));
  }
  for (const double scale : {0.5, 1.0, 1.7}) {
    WordGroupOptions o;
    o.radius_scale = scale;
    const GroupVector g = buildWordGroups(kps, words, o);
    EXPECT_FALSE(g.empty());
    EXPECT_EQ(g, bruteForceGroups(kps, words, scale)) << "radius_scale " << scale;
  }
}

TEST(WordGroups, GridSearchMatchesAllPairsOnClustersWithMixedScales) {
  // Multi-scale sizes (ORB-like 31 * 1.2^level, plus tiny GFTT-like ones)
  // around a few tight clusters far apart, so the grid is mostly empty.
  std::mt19937 rng(3);
  std::normal_distribution<float> jitter(0.f, 6.f);
  std::uniform_int_distribution<int> level(0, 7), cluster(0, 4), tiny(0, 3);
  const float centres[5][2] = {{10, 10}, {600, 20}, {320, 240}, {30, 470}, {5000, 4000}};
  std::vector<Keypoint> kps;
  std::vector<WordId> words;
  for (int i = 0; i < 400; ++i) {
    const int c = cluster(rng);
    const float size = tiny(rng) == 0 ? 3.f : 31.f * std::pow(1.2f, level(rng));
    kps.push_back(kp(centres[c][0] + jitter(rng), centres[c][1] + jitter(rng), size));
    words.push_back(static_cast<WordId>(i % 97));
  }
  const GroupVector g = buildWordGroups(kps, words, WordGroupOptions());
  EXPECT_FALSE(g.empty());
  EXPECT_EQ(g, bruteForceGroups(kps, words, 1.0));
}

TEST(WordGroups, PointsAtTheRadiusDecideAsTheDoubleDistanceDoes) {
  // The scan compares float distances and counts a run again in double when
  // one lies within 2e-6 (relative) of the radius. Around centres of
  // several sizes: points at the radius and up to 3e-6 of it inside and
  // outside, among them points where the float distance alone decides
  // otherwise than the double one. The groups must be the definition's
  // (brute force in double).
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> angle(0.0, 6.283), offset(-3e-6, 3e-6);
  std::vector<Keypoint> kps;
  std::vector<WordId> words;
  const float centres[3][3] = {
      {321.37f, 211.93f, 31.f}, {77.1f, 400.2f, 44.64f}, {600.9f, 30.3f, 7.3f}};
  int float_disagrees = 0;
  WordId word = 0;
  for (const auto& c : centres) {
    kps.push_back(kp(c[0], c[1], c[2]));
    words.push_back(word++);
    const double r2 = static_cast<double>(c[2]) * c[2];
    // 300 points off the ring by up to 3e-6 of the radius, and those of
    // 20,000 on it where float and double disagree (a few per cent).
    for (int k = 0; k < 20300; ++k) {
      const double a = angle(rng), r = c[2] * (1.0 + (k < 300 ? offset(rng) : 0.0));
      const float x = static_cast<float>(c[0] + r * std::cos(a));
      const float y = static_cast<float>(c[1] + r * std::sin(a));
      const float fx = x - c[0], fy = y - c[1];
      const double dx = static_cast<double>(x) - c[0], dy = static_cast<double>(y) - c[1];
      const bool disagree =
          (fx * fx + fy * fy < static_cast<float>(r2)) != (dx * dx + dy * dy < r2);
      if (k >= 300 && !disagree) continue;
      float_disagrees += disagree;
      // Size 0: the ring's points have no group of their own.
      kps.push_back(kp(x, y, 0.f));
      words.push_back(1000);
    }
  }
  EXPECT_GE(float_disagrees, 100) << "the rings should hold points where float decides otherwise";
  const GroupVector g = buildWordGroups(kps, words, WordGroupOptions());
  EXPECT_EQ(g, bruteForceGroups(kps, words, 1.0));
  EXPECT_EQ(g.size(), 3u);

  // Only the points where the float distance is strictly on the other side
  // of the float radius (no ties, which send a run to double anyway): the
  // band alone must catch them.
  std::vector<Keypoint> strict;
  std::vector<WordId> strict_words;
  int strict_disagrees = 0;
  for (int ci = 0; ci < 3; ++ci) {
    const auto& c = centres[ci];
    strict.push_back(kp(c[0], c[1], c[2]));
    strict_words.push_back(static_cast<WordId>(ci));
    const double r2 = static_cast<double>(c[2]) * c[2];
    for (int k = 0; k < 20000; ++k) {
      const double a = angle(rng);
      const float x = static_cast<float>(c[0] + c[2] * std::cos(a));
      const float y = static_cast<float>(c[1] + c[2] * std::sin(a));
      const float fx = x - c[0], fy = y - c[1];
      const float d2f = fx * fx + fy * fy;
      const double dx = static_cast<double>(x) - c[0], dy = static_cast<double>(y) - c[1];
      if (d2f == static_cast<float>(r2) ||
          (d2f < static_cast<float>(r2)) == (dx * dx + dy * dy < r2))
        continue;
      ++strict_disagrees;
      strict.push_back(kp(x, y, 0.f));
      strict_words.push_back(1000);
    }
  }
  EXPECT_GE(strict_disagrees, 20);
  EXPECT_EQ(buildWordGroups(strict, strict_words, WordGroupOptions()),
            bruteForceGroups(strict, strict_words, 1.0));
}

TEST(WordGroups, FarCoordinatesAndTinyRadiiAreCountedInDouble) {
  // Beyond 1e6 pixels or below 1e-3 the float test does not apply.
  // Far: k0's radius 40 holds k1 at 32; k1's radius 1 does not hold k0.
  const std::vector<Keypoint> far{kp(2e6f, 3e6f, 40.f), kp(2e6f + 32.f, 3e6f, 1.f)};
  const GroupVector g_far = buildWordGroups(far, {1, 2}, WordGroupOptions());
  EXPECT_EQ(g_far, bruteForceGroups(far, {1, 2}, 1.0));
  EXPECT_EQ(g_far, (GroupVector{{1, 1.0}}));
  // Tiny: k0's radius 5e-4 holds k1 at 3e-4, k1's radius 2e-4 does not
  // hold k0.
  const std::vector<Keypoint> tiny{kp(5.f, 5.f, 5e-4f), kp(5.f + 3e-4f, 5.f, 2e-4f)};
  const GroupVector g_tiny = buildWordGroups(tiny, {3, 4}, WordGroupOptions());
  EXPECT_EQ(g_tiny, bruteForceGroups(tiny, {3, 4}, 1.0));
  EXPECT_EQ(g_tiny, (GroupVector{{3, 1.0}}));
}

TEST(WordGroups, TinyRadiiOverAHugeExtentStayCorrect) {
  // Cell size would be 0.01 over an extent of 1e9: the grid must widen its
  // cells instead of overflowing the cell coordinates.
  const std::vector<Keypoint> kps{kp(0, 0, 0.01f), kp(0.005f, 0, 0.01f), kp(1e9f, 1e9f, 0.01f),
                                  kp(1e9f, 1e9f, 0.01f)};
  const std::vector<WordId> words{1, 2, 3, 4};
  const GroupVector g = buildWordGroups(kps, words, WordGroupOptions());
  const GroupVector expected{{1, 1.0}, {2, 1.0}, {3, 1.0}, {4, 1.0}};
  EXPECT_EQ(g, expected);
}

}  // namespace
}  // namespace bowg
