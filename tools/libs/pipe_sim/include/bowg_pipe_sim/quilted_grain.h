// A wall grain quilted from real images: square patches cut from grey-level
// photographs (e.g. sewer CCTV frames), placed on a grid and blended over
// their overlap, so that a robustness run can check that a detector tuned on
// the procedural grain also works on the statistics of a real pipe wall.
// Which patch goes where is a function of (seed, patch index) only (SplitMix64
// hashes), like everything else in the generator. WallTexture uses it in
// place of the procedural noise and pits when WallTextureOptions has images.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace bowg {
namespace pipe_sim {

class QuiltedGrain {
 public:
  static constexpr int kPatch = 48;    ///< patch side (texels = mm of wall)
  static constexpr int kOverlap = 12;  ///< feathered overlap of neighbours

  /// `images`: non-empty grey CV_8U images, each at least kPatch x kPatch.
  /// Throws std::invalid_argument naming the offending image.
  explicit QuiltedGrain(const std::vector<cv::Mat>& images);

  /// A rows x cols CV_32F field with mean 0 and standard deviation 1,
  /// periodic in the column direction (the circumference has no seam), a
  /// function of the images and `seed` only.
  cv::Mat field(int rows, int cols, std::uint64_t seed) const;

 private:
  cv::Mat patch(std::uint64_t seed, long index) const;

  std::vector<cv::Mat> images_;  // CV_32F in [0, 1]
  std::vector<double> means_;
};

/// The grey levels of the PNG and JPG files (by extension, any case) in
/// `dir`, read with cv::imread in sorted file-name order (the order is part
/// of the output), with a fraction `crop` of the rows cut away at the top and
/// at the bottom (CCTV frames carry a burned-in text overlay there).
/// Throws std::invalid_argument for crop outside [0, 0.45], std::runtime_error
/// naming the folder or file when the folder cannot be read, holds no image,
/// or an image cannot be decoded.
std::vector<cv::Mat> loadGrainImages(const std::string& dir, double crop);

}  // namespace pipe_sim
}  // namespace bowg
