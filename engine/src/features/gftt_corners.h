// GFTT (Shi-Tomasi or Harris) corners, selected exactly as
// cv::goodFeaturesToTrack selects them, in buffers kept between calls.
//
// Why not cv::goodFeaturesToTrack itself: it allocates and frees ~8 MB of
// float images per 640x480 frame (the corner response, its dilation and the
// derivatives behind them). Freed together at the top of the heap, that
// memory goes back to the system on most frames and is faulted in again on
// the next: with the pipe GFTT preset, 526 brk calls in 80 frames and 28.7 ms
// of features a frame on the development VM, against 81 calls and 6.7 ms
// with the response and its dilation in buffers kept per thread, as here
// (README, "CPU budget"). Only OpenCV's corner response allocates now.
#ifndef BOWG_FEATURES_GFTT_CORNERS_H
#define BOWG_FEATURES_GFTT_CORNERS_H

#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

namespace bowg {

// cv::goodFeaturesToTrack's arguments. The extractor sets the first five
// from FeatureOptions (gftt_*); the derivative aperture (Sobel 3x3) and the
// Harris free parameter stay at OpenCV's defaults, as here.
struct GfttCornerOptions {
  int max_corners = 0;          ///< 0 = no limit
  double quality_level = 0.01;  ///< of the strongest response
  double min_distance = 1.0;    ///< px between kept corners
  int block_size = 3;
  bool use_harris = false;
  int gradient_size = 3;
  double harris_k = 0.04;
};

/// The corners of 8-bit `image` (where `mask`, if not empty, is non-zero)
/// and their responses, strongest first: what cv::goodFeaturesToTrack returns
/// for the same arguments, element for element. `level` picks the thread's
/// buffer set (one per pyramid level, so that each keeps its size).
void detectGfttCorners(const cv::Mat& image, const cv::Mat& mask, const GfttCornerOptions& o,
                       std::vector<cv::Point2f>& corners, std::vector<float>& quality,
                       std::size_t level = 0);

}  // namespace bowg

#endif  // BOWG_FEATURES_GFTT_CORNERS_H
