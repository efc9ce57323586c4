#include "bowg_pipe_sim/quilted_grain.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bowg_pipe_sim/random.h"

namespace bowg {
namespace pipe_sim {
namespace {

// A patch darker than this fraction of its image's mean is most likely the
// unlit far pipe of a CCTV frame, not wall: drawn again (a few times).
constexpr double kDarkFraction = 0.5;
constexpr int kAttempts = 8;
// Contrast floor of the per-patch normalisation (albedo units, ~2.5 grey
// levels): a flat patch is not blown up into amplified compression noise.
constexpr double kMinPatchSpread = 0.01;

/// Linear feather: 1 inside, falling to ~0 across the overlap at both ends.
float feather(int i) {
  const int p = QuiltedGrain::kPatch, o = QuiltedGrain::kOverlap;
  return static_cast<float>(std::min(1.0, std::min((i + 0.5) / o, (p - i - 0.5) / o)));
}

}  // namespace

QuiltedGrain::QuiltedGrain(const std::vector<cv::Mat>& images) {
  if (images.empty()) throw std::invalid_argument("QuiltedGrain: no images");
  for (std::size_t i = 0; i < images.size(); ++i) {
    const cv::Mat& im = images[i];
    if (im.type() != CV_8UC1 || im.rows < kPatch || im.cols < kPatch) {
      throw std::invalid_argument("QuiltedGrain: image " + std::to_string(i) +
                                  " must be grey 8-bit and at least " + std::to_string(kPatch) +
                                  " x " + std::to_string(kPatch) + " px");
    }
    cv::Mat f;
    im.convertTo(f, CV_32F, 1.0 / 255);
    images_.push_back(f);
    means_.push_back(cv::mean(f)[0]);
  }
}

cv::Mat QuiltedGrain::patch(std::uint64_t seed, long index) const {
  const std::uint64_t base = hashCombine(seed, 0x7175696c74ULL, static_cast<std::uint64_t>(index));
  cv::Mat p;
  for (int a = 0; a < kAttempts; ++a) {
    const std::uint64_t h = hashCombine(base, static_cast<std::uint64_t>(a));
    const std::size_t k = static_cast<std::size_t>(toUnit(h) * images_.size());
    const cv::Mat& im = images_[k];
    const int x = static_cast<int>(toUnit(hashCombine(h, 1)) * (im.cols - kPatch + 1));
    const int y = static_cast<int>(toUnit(hashCombine(h, 2)) * (im.rows - kPatch + 1));
    p = im(cv::Rect(x, y, kPatch, kPatch));
    if (cv::mean(p)[0] >= kDarkFraction * means_[k]) break;
  }
  // Mirror images of a patch are as plausible a wall as the patch itself and
  // multiply the variety of a small image set by four.
  const std::uint64_t flips = hashCombine(base, 0x666c6970ULL) >> 62;
  cv::Mat out;
  if (flips == 0) out = p.clone();
  else cv::flip(p, out, flips == 1 ? 0 : flips == 2 ? 1 : -1);
  // Only the texture, not the lighting of the photograph: zero mean, unit
  // spread per patch.
  cv::Scalar mean, spread;
  cv::meanStdDev(out, mean, spread);
  out = (out - mean[0]) / std::max(spread[0], kMinPatchSpread);
  return out;
}

cv::Mat QuiltedGrain::field(int rows, int cols, std::uint64_t seed) const {
  const int step = kPatch - kOverlap;
  const int grid_rows = std::max(1, (rows - kOverlap + step - 1) / step);
  // Columns wrap: as many patches as cover the circumference, spread evenly
  // (their spacing is at most `step`, so neighbours overlap at least kOverlap).
  const int grid_cols = std::max(1, (cols + step - 1) / step);
  cv::Mat sum = cv::Mat::zeros(rows, cols, CV_32F), weight2 = cv::Mat::zeros(rows, cols, CV_32F);
  for (int i = 0; i < grid_rows; ++i) {
    for (int j = 0; j < grid_cols; ++j) {
      const cv::Mat p = patch(seed, static_cast<long>(i) * grid_cols + j);
      const int r0 = i * step, c0 = static_cast<int>(static_cast<long>(j) * cols / grid_cols);
      for (int y = 0; y < kPatch && r0 + y < rows; ++y) {
        const float wy = feather(y);
        const float* in = p.ptr<float>(y);
        float* s = sum.ptr<float>(r0 + y);
        float* w2 = weight2.ptr<float>(r0 + y);
        for (int x = 0; x < kPatch; ++x) {
          const int c = (c0 + x) % cols;
          const float w = wy * feather(x);
          s[c] += w * in[x];
          w2[c] += w * w;
        }
      }
    }
  }
  // Dividing by sqrt(sum w^2) instead of sum w keeps the variance of
  // independent patches in the overlaps: no grid of low-contrast stripes.
  cv::Mat norm;
  cv::sqrt(weight2, norm);
  cv::Mat out = sum / norm;
  cv::Scalar mean, spread;
  cv::meanStdDev(out, mean, spread);
  out = (out - mean[0]) / std::max(spread[0], 1e-6);
  return out;
}

}  // namespace pipe_sim
}  // namespace bowg
