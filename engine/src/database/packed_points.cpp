#include "bowg/database/packed_points.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "bowg/core/heap_bytes.h"

namespace bowg {

#if __cplusplus < 201703L
constexpr std::uint32_t PackedPoints::kExactFlag;
constexpr int PackedPoints::kLevelBits;
constexpr int PackedPoints::kXBits;
constexpr int PackedPoints::kYBits;
constexpr int PackedPoints::kMaxLevel;
#endif

namespace {

constexpr std::uint32_t kXMax = (1u << PackedPoints::kXBits) - 1;
constexpr std::uint32_t kYMax = (1u << PackedPoints::kYBits) - 1;

bool validFactor(float scale_factor) { return std::isfinite(scale_factor) && scale_factor > 0.f; }

// The level coordinate whose product with `scale` is `v` bit for bit, or -1.
// Bits, not ==: -0.0 == 0.0, and a point must come back as it was given.
long levelCoordinate(float v, float scale, std::uint32_t max) {
  if (!(v >= 0.f) || !(scale > 0.f)) return -1;
  // v >= 0: truncating q + 0.5 rounds to the nearest (no libm call); the
  // check below decides.
  const double q = static_cast<double>(v) / static_cast<double>(scale) + 0.5;
  if (!(q < static_cast<double>(max) + 1.0)) return -1;
  const long c = static_cast<long>(q);
  const float back = static_cast<float>(c) * scale;
  return std::memcmp(&back, &v, sizeof v) == 0 ? c : -1;
}

// The levels' scales, each computed when first needed: std::pow costs as
// much as packing a few dozen points, and most entries use few levels.
class LevelScales {
 public:
  explicit LevelScales(float factor) : factor_(factor) {}
  float operator()(int level) {
    const std::uint32_t bit = 1u << level;
    if (!(known_ & bit)) {
      scales_[level] = pyramidLevelScale(factor_, level);
      known_ |= bit;
    }
    return scales_[level];
  }

 private:
  float factor_;
  std::uint32_t known_ = 0;
  float scales_[PackedPoints::kMaxLevel + 1] = {};
};

std::uint32_t code(int level, long ix, long iy) {
  return (static_cast<std::uint32_t>(level) << (PackedPoints::kXBits + PackedPoints::kYBits)) |
         (static_cast<std::uint32_t>(ix) << PackedPoints::kYBits) | static_cast<std::uint32_t>(iy);
}

}  // namespace

float pyramidLevelScale(float scale_factor, int level) {
  return static_cast<float>(
      std::pow(static_cast<double>(scale_factor), static_cast<double>(level)));
}

PackedPoints::PackedPoints(const std::vector<ImagePoint>& points, float scale_factor,
                           const std::vector<int>& octave_hints)
    : scale_factor_(validFactor(scale_factor) ? scale_factor : 0.f) {
  const int levels = scale_factor_ > 0.f ? kMaxLevel + 1 : 1;
  LevelScales scales(scale_factor_);
  if (points.size() > (kExactFlag - 1) / 3) {
    throw std::length_error("PackedPoints: too many points");
  }
  size_ = static_cast<std::uint32_t>(points.size());
  codes_.reserve(points.size());
  std::vector<ImagePoint> exact;
  const auto tryLevel = [&](const ImagePoint& p, int l, std::uint32_t* out) {
    if (l < 0 || l >= levels) return false;
    const float s = scales(l);
    const long ix = levelCoordinate(p.x, s, kXMax);
    const long iy = ix < 0 ? -1 : levelCoordinate(p.y, s, kYMax);
    if (iy < 0) return false;
    *out = code(l, ix, iy);
    return true;
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ImagePoint& p = points[i];
    std::uint32_t c = 0;
    bool packed = i < octave_hints.size() && tryLevel(p, octave_hints[i], &c);
    for (int l = 0; !packed && l < levels; ++l) packed = tryLevel(p, l, &c);
    if (!packed) {
      c = kExactFlag | static_cast<std::uint32_t>(exact.size());
      exact.push_back(p);
    }
    codes_.push_back(c);
  }
  // Exact floats are the exception: appended after the codes, no slack.
  if (!exact.empty()) {
    codes_.reserve(codes_.size() + 2 * exact.size());
    for (const ImagePoint& p : exact) {
      std::uint32_t bits[2];
      std::memcpy(&bits[0], &p.x, 4);
      std::memcpy(&bits[1], &p.y, 4);
      codes_.push_back(bits[0]);
      codes_.push_back(bits[1]);
    }
  }
}

ImagePoint PackedPoints::exact(std::uint32_t code) const {
  const std::size_t at = size_ + 2 * static_cast<std::size_t>(code & ~kExactFlag);
  ImagePoint p;
  std::memcpy(&p.x, &codes_[at], 4);
  std::memcpy(&p.y, &codes_[at + 1], 4);
  return p;
}

PackedPoints PackedPoints::fromKeypoints(const std::vector<Keypoint>& keypoints,
                                         float scale_factor) {
  std::vector<int> octaves(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) octaves[i] = keypoints[i].octave;
  return PackedPoints(imagePoints(keypoints), scale_factor, octaves);
}

ImagePoint PackedPoints::operator[](std::size_t i) const {
  const std::uint32_t c = codes_[i];
  if (c & kExactFlag) return exact(c);
  const float s = pyramidLevelScale(scale_factor_, static_cast<int>(c >> (kXBits + kYBits)));
  return ImagePoint{static_cast<float>((c >> kYBits) & kXMax) * s,
                    static_cast<float>(c & kYMax) * s};
}

void PackedPoints::unpack(std::vector<ImagePoint>* out) const {
  LevelScales scales(scale_factor_);
  out->resize(size_);
  for (std::size_t i = 0; i < size_; ++i) {
    const std::uint32_t c = codes_[i];
    if (c & kExactFlag) {
      (*out)[i] = exact(c);
      continue;
    }
    const float s = scales(static_cast<int>(c >> (kXBits + kYBits)));
    (*out)[i] = ImagePoint{static_cast<float>((c >> kYBits) & kXMax) * s,
                           static_cast<float>(c & kYMax) * s};
  }
}

std::vector<ImagePoint> PackedPoints::unpack() const {
  std::vector<ImagePoint> out;
  unpack(&out);
  return out;
}

std::size_t PackedPoints::heapBytes() const { return vectorHeapBytes(codes_); }

}  // namespace bowg
