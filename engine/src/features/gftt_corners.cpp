#include "features/gftt_corners.h"

#include <algorithm>
#include <memory>
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

// One set per pyramid level: a level's buffers keep their size from frame
// to frame instead of being reallocated for the next level's.
GfttBuffers& threadBuffers(std::size_t level) {
  thread_local std::vector<GfttBuffers> buffers;
  if (buffers.size() <= level) buffers.resize(level + 1);
  return buffers[level];
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

// The kept corners by cell of min_distance px, as goodFeaturesToTrack
// spaces them: a corner is kept when it is at least min_distance from every
// kept corner of the 3x3 cells around its own.
class SpacingGrid {
 public:
  SpacingGrid(std::vector<std::vector<cv::Point2f>>* cells, const cv::Size& image, double min_d)
      : cells_(cells),
        cell_(cvRound(min_d)),
        w_((image.width + cell_ - 1) / cell_),
        h_((image.height + cell_ - 1) / cell_),
        min_d2_(min_d * min_d) {
    cells_->resize(static_cast<std::size_t>(w_) * h_);
    for (std::vector<cv::Point2f>& c : *cells_) c.clear();
  }

  // Keeps `p` (true) when no kept corner is nearer than min_distance.
  bool admit(cv::Point2f p) {
    const int cx = static_cast<int>(p.x) / cell_, cy = static_cast<int>(p.y) / cell_;
    for (int yy = std::max(0, cy - 1); yy <= std::min(h_ - 1, cy + 1); ++yy) {
      for (int xx = std::max(0, cx - 1); xx <= std::min(w_ - 1, cx + 1); ++xx) {
        for (const cv::Point2f& k : (*cells_)[yy * w_ + xx]) {
          const float dx = p.x - k.x, dy = p.y - k.y;
          if (dx * dx + dy * dy < min_d2_) return false;
        }
      }
    }
    (*cells_)[cy * w_ + cx].push_back(p);
    return true;
  }

 private:
  std::vector<std::vector<cv::Point2f>>* cells_;
  int cell_, w_, h_;
  double min_d2_;
};

}  // namespace

void detectGfttCorners(const cv::Mat& image, const cv::Mat& mask, const GfttCornerOptions& o,
                       std::vector<cv::Point2f>& corners, std::vector<float>& quality,
                       std::size_t level) {
  corners.clear();
  quality.clear();
  if (image.empty()) return;
  GfttBuffers& b = threadBuffers(level);
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

  // Below 1 px goodFeaturesToTrack keeps every candidate.
  std::unique_ptr<SpacingGrid> grid;
  if (o.min_distance >= 1) grid.reset(new SpacingGrid(&b.grid, image.size(), o.min_distance));
  for (const float* c : b.candidates) {
    const cv::Point2f p = pixelOf(b.response, c);
    if (grid && !grid->admit(p)) continue;
    corners.push_back(p);
    quality.push_back(*c);
    if (o.max_corners > 0 && static_cast<int>(corners.size()) == o.max_corners) break;
  }
}

}  // namespace bowg
