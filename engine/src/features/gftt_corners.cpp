#include "features/gftt_corners.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace bowg {
namespace {

// The buffers one thread reuses from frame to frame.
struct GfttBuffers {
  cv::Mat response;  // corner response, then thresholded
  cv::Mat dilated;   // its 3x3 maximum
  std::vector<const float*> candidates;
  std::vector<std::vector<cv::Point2f>> grid;
};

GfttBuffers& threadBuffers() {
  thread_local GfttBuffers buffers;
  return buffers;
}

// Strongest first; equal responses by address, the later pixel first: the
// order cv::goodFeaturesToTrack sorts its candidates in.
bool strongerFirst(const float* a, const float* b) {
  return (*a > *b) ? true : (*a < *b) ? false : (a > b);
}

// Local maxima of the thresholded response inside the 1-pixel border (and
// the mask): the candidates, as pointers into `response`.
void collectCandidates(GfttBuffers& b, const cv::Mat& mask) {
  b.candidates.clear();
  for (int y = 1; y < b.response.rows - 1; ++y) {
    const float* r = b.response.ptr<float>(y);
    const float* d = b.dilated.ptr<float>(y);
    const uchar* m = mask.empty() ? nullptr : mask.ptr<uchar>(y);
    for (int x = 1; x < b.response.cols - 1; ++x) {
      if (r[x] != 0 && r[x] == d[x] && (!m || m[x])) b.candidates.push_back(r + x);
    }
  }
  std::sort(b.candidates.begin(), b.candidates.end(), strongerFirst);
}

cv::Point2f pixelOf(const cv::Mat& response, const float* p) {
  const std::size_t offset =
      static_cast<std::size_t>(reinterpret_cast<const uchar*>(p) - response.data);
  const int y = static_cast<int>(offset / response.step);
  const int x = static_cast<int>((offset - y * response.step) / sizeof(float));
  return cv::Point2f(static_cast<float>(x), static_cast<float>(y));
}

// Whether `p` is at least min_distance (squared: `min_d2`) from every kept
// corner of the 3x3 grid cells around it (cells of min_distance px).
bool farFromKept(const GfttBuffers& b, cv::Point2f p, int cell, int grid_w, int grid_h,
                 double min_d2) {
  const int cx = static_cast<int>(p.x) / cell, cy = static_cast<int>(p.y) / cell;
  for (int yy = std::max(0, cy - 1); yy <= std::min(grid_h - 1, cy + 1); ++yy) {
    for (int xx = std::max(0, cx - 1); xx <= std::min(grid_w - 1, cx + 1); ++xx) {
      for (const cv::Point2f& k : b.grid[yy * grid_w + xx]) {
        const float dx = p.x - k.x, dy = p.y - k.y;
        if (dx * dx + dy * dy < min_d2) return false;
      }
    }
  }
  return true;
}

}  // namespace

void detectGfttCorners(const cv::Mat& image, const cv::Mat& mask, const GfttCornerOptions& o,
                       std::vector<cv::Point2f>& corners, std::vector<float>& quality) {
  corners.clear();
  quality.clear();
  if (image.empty()) return;
  GfttBuffers& b = threadBuffers();
  if (o.use_harris) {
    cv::cornerHarris(image, b.response, o.block_size, o.gradient_size, o.harris_k);
  } else {
    cv::cornerMinEigenVal(image, b.response, o.block_size, o.gradient_size);
  }
  double strongest = 0;
  cv::minMaxLoc(b.response, nullptr, &strongest, nullptr, nullptr, mask);
  cv::threshold(b.response, b.response, strongest * o.quality_level, 0, cv::THRESH_TOZERO);
  cv::dilate(b.response, b.dilated, cv::Mat());
  collectCandidates(b, mask);

  const bool spaced = o.min_distance >= 1;
  const int cell = spaced ? cvRound(o.min_distance) : 1;
  const int grid_w = (image.cols + cell - 1) / cell, grid_h = (image.rows + cell - 1) / cell;
  if (spaced) {
    b.grid.resize(static_cast<std::size_t>(grid_w) * grid_h);
    for (std::vector<cv::Point2f>& g : b.grid) g.clear();
  }
  const double min_d2 = o.min_distance * o.min_distance;
  for (const float* c : b.candidates) {
    const cv::Point2f p = pixelOf(b.response, c);
    if (spaced) {
      if (!farFromKept(b, p, cell, grid_w, grid_h, min_d2)) continue;
      b.grid[(static_cast<int>(p.y) / cell) * grid_w + static_cast<int>(p.x) / cell].push_back(p);
    }
    corners.push_back(p);
    quality.push_back(*c);
    if (o.max_corners > 0 && static_cast<int>(corners.size()) == o.max_corners) break;
  }
}

}  // namespace bowg
