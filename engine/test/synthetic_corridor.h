// Synthetic keyframes for the database, loop-detector and persistence tests
// and the pipeline benchmark: a straight corridor wall of 3D landmarks, each
// with its own random 256-bit descriptor, observed by a pinhole camera that
// translates along the wall. Consecutive keyframes share most landmarks (so the
// previous-keyframe normaliser is healthy); passing the same x again is a true
// revisit with real two-view geometry (the landmarks have depth variation, so
// the fundamental matrix is well defined).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/database/packed_points.h"
#include "bowg/detection/loop_detector.h"

namespace bowg {
namespace testing {

struct Landmark {
  double x, y, z;
  Descriptor descriptor;
};

struct Corridor {
  std::vector<Landmark> landmarks;  ///< sorted by x
  double length = 0;
};

inline CameraIntrinsics corridorCamera() {
  CameraIntrinsics k;
  k.valid = true;
  k.fx = k.fy = 400;
  k.cx = 320;
  k.cy = 240;
  return k;
}

/// Landmarks uniformly on x in [0, length], y in [-2.5, 2.5], depth z in
/// [4, 6]: about `per_metre` of them per metre (~8 m of wall per 640x480 view
/// at z = 5 with fx = 400, so per_metre = 50 gives ~400 features).
inline Corridor makeCorridor(double length, int per_metre, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0.0, length), uy(-2.5, 2.5), uz(4.0, 6.0);
  Corridor c;
  c.length = length;
  const std::size_t n = static_cast<std::size_t>(length * per_metre);
  c.landmarks.resize(n);
  for (auto& l : c.landmarks) {
    l.x = ux(rng);
    l.y = uy(rng);
    l.z = uz(rng);
    for (auto& b : l.descriptor.bits) b = rng();
  }
  std::sort(c.landmarks.begin(), c.landmarks.end(),
            [](const Landmark& a, const Landmark& b) { return a.x < b.x; });
  return c;
}

/// The keyframe seen from camera position (cam_x, 0, 0), optical axis +z:
/// landmarks projecting inside the 640x480 image, each descriptor with
/// `bit_flips` random bits flipped and the pixel position with Gaussian noise
/// of `pixel_noise` px. Keypoint size (the word-group radius) `size_px`.
inline KeyframeInput observeCorridor(const Corridor& c, double cam_x, double stamp,
                                     std::mt19937_64& rng, int bit_flips = 0,
                                     double pixel_noise = 0.0, float size_px = 30.f) {
  const CameraIntrinsics k = corridorCamera();
  KeyframeInput kf;
  kf.stamp = stamp;
  kf.intrinsics = k;
  kf.features.image_width = 640;
  kf.features.image_height = 480;
  std::normal_distribution<double> noise(0.0, pixel_noise > 0 ? pixel_noise : 1.0);
  std::uniform_int_distribution<int> bit(0, 255);
  // Only landmarks with |x - cam_x| < z * cx / fx can be visible (z <= 6).
  const double reach = 6.0 * k.cx / k.fx + 0.1;
  auto lo = std::lower_bound(c.landmarks.begin(), c.landmarks.end(), cam_x - reach,
                             [](const Landmark& l, double x) { return l.x < x; });
  for (auto it = lo; it != c.landmarks.end() && it->x < cam_x + reach; ++it) {
    const double u = k.fx * (it->x - cam_x) / it->z + k.cx;
    const double v = k.fy * it->y / it->z + k.cy;
    if (u < 0 || u >= 640 || v < 0 || v >= 480) continue;
    Keypoint kp;
    kp.x = static_cast<float>(u + (pixel_noise > 0 ? noise(rng) : 0.0));
    kp.y = static_cast<float>(v + (pixel_noise > 0 ? noise(rng) : 0.0));
    kp.size = size_px;
    Descriptor d = it->descriptor;
    for (int f = 0; f < bit_flips; ++f) {
      const int b = bit(rng);
      d.bits[b / 64] ^= (1ull << (b % 64));
    }
    kf.features.keypoints.push_back(kp);
    kf.features.descriptors.push_back(d);
  }
  return kf;
}

/// Moves every keypoint of `kf` onto the integer grid of a pyramid level, as
/// OpenCV's ORB places them (x = integer * scale_factor^octave), with the
/// octaves shared as ORB shares its features between `levels` levels (level
/// l gets a share proportional to scale_factor^-l), so that the database
/// packs the positions as it packs real ORB keypoints (PackedPoints).
inline void placeOnOrbPyramid(KeyframeInput* kf, float scale_factor = 1.2f, int levels = 8) {
  const double f = 1.0 / scale_factor;
  std::vector<double> cumulative(static_cast<std::size_t>(levels));
  double sum = 0;
  for (int l = 0; l < levels; ++l) cumulative[static_cast<std::size_t>(l)] = sum += std::pow(f, l);
  kf->features.pyramid_scale_factor = scale_factor;
  for (std::size_t i = 0; i < kf->features.keypoints.size(); ++i) {
    // A low-discrepancy sequence spreads the octaves over the keypoints.
    const double u = std::fmod(0.6180339887498949 * static_cast<double>(i + 1), 1.0) * sum;
    int octave = 0;
    while (octave + 1 < levels && u >= cumulative[static_cast<std::size_t>(octave)]) ++octave;
    Keypoint& k = kf->features.keypoints[i];
    const float s = pyramidLevelScale(scale_factor, octave);
    k.octave = octave;
    k.x = static_cast<float>(std::max(0.f, std::round(k.x / s))) * s;
    k.y = static_cast<float>(std::max(0.f, std::round(k.y / s))) * s;
  }
}

}  // namespace testing
}  // namespace bowg
