// A database entry's keypoint positions in 4 bytes each instead of 8,
// losslessly. A multi-scale detector such as OpenCV's ORB finds a keypoint on
// the integer pixel grid of one pyramid level and reports it in image pixels
// as that integer times the level's scale, a float product:
//   x = float(ix) * s_l,  s_l = float(scale_factor^l)   (OpenCV's getScale).
// Such a point is kept as (l, ix, iy) in one 32-bit code; any other point
// (sub-pixel refinement, a foreign detector, a coordinate out of range) keeps
// its two floats. Packing checks that the code reproduces both floats
// exactly, so reading back always returns the positions that were given:
// RANSAC's outcome, and so every loop, is unchanged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

/// The scale of pyramid level `level` as OpenCV computes it:
/// float(double(scale_factor) ^ level). 1 at level 0 for any factor.
float pyramidLevelScale(float scale_factor, int level);

class PackedPoints {
 public:
  /// Code layout: bit 31 clear: level in bits 27-30, ix in bits 13-26, iy in
  /// bits 0-12 (level coordinates up to 16383 x 8191); bit 31 set: the low
  /// 31 bits index the exact floats, kept as bit patterns after the codes
  /// in the same block (one allocation per entry).
  static constexpr std::uint32_t kExactFlag = 0x80000000u;
  static constexpr int kLevelBits = 4, kXBits = 14, kYBits = 13;
  static constexpr int kMaxLevel = (1 << kLevelBits) - 1;

  PackedPoints() = default;
  /// Packs `points`. `scale_factor`: the pyramid's (<= 0 or not finite: no
  /// pyramid, only integer level-0 positions pack). `octave_hints`, when not
  /// empty, index-aligned: the level to try first for each point (the
  /// keypoint's octave); every level is tried after it.
  PackedPoints(const std::vector<ImagePoint>& points, float scale_factor,
               const std::vector<int>& octave_hints = {});
  /// Packs keypoints' positions with their octaves as hints.
  static PackedPoints fromKeypoints(const std::vector<Keypoint>& keypoints, float scale_factor);

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  float scaleFactor() const { return scale_factor_; }
  /// Points kept as two floats (no level reproduces them).
  std::size_t exactCount() const { return (codes_.size() - size_) / 2; }

  /// Point `i`, bit for bit as given to the constructor.
  ImagePoint operator[](std::size_t i) const;
  /// Every point, in order, into `out` (resized; its capacity is reused).
  void unpack(std::vector<ImagePoint>* out) const;
  std::vector<ImagePoint> unpack() const;

  /// Heap bytes held (the block's capacity).
  std::size_t heapBytes() const;

 private:
  ImagePoint exact(std::uint32_t code) const;

  std::vector<std::uint32_t> codes_;  ///< size_ codes, then 2 words per exact point
  std::uint32_t size_ = 0;
  float scale_factor_ = 0.f;
};

}  // namespace bowg
