// JPEG thumbnails of the keyframes (see keyframe_thumbnails.h).
#include "bowg_ros/keyframe_thumbnails.h"

#include <algorithm>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace bowg_ros {

void ThumbnailOptions::validate() const {
  if (max_side < 0) throw std::invalid_argument("debug_thumbnail_size must be >= 0 px");
  if (jpeg_quality < 1 || jpeg_quality > 100) {
    throw std::invalid_argument("thumbnail JPEG quality must lie in [1, 100]");
  }
}

KeyframeThumbnails::KeyframeThumbnails(const ThumbnailOptions& options) : options_(options) {
  options_.validate();
}

void KeyframeThumbnails::add(std::uint32_t id, const cv::Mat& image) {
  if (options_.max_side == 0 || image.empty()) return;
  const int longest = std::max(image.cols, image.rows);
  cv::Mat small = image;
  if (longest > options_.max_side) {
    const double f = double(options_.max_side) / longest;
    // INTER_AREA: a thumbnail without aliasing of the wall texture.
    cv::resize(image, small,
               cv::Size(std::max(1, int(image.cols * f + 0.5)), std::max(1, int(image.rows * f + 0.5))),
               0, 0, cv::INTER_AREA);
  }
  Thumbnail t;
  t.original = image.size();
  cv::imencode(".jpg", small, t.jpeg, {cv::IMWRITE_JPEG_QUALITY, options_.jpeg_quality});
  auto it = thumbnails_.find(id);
  if (it != thumbnails_.end()) {
    bytes_ -= it->second.jpeg.size();
    thumbnails_.erase(it);
  }
  bytes_ += t.jpeg.size();
  thumbnails_.emplace(id, std::move(t));
}

cv::Mat KeyframeThumbnails::restore(std::uint32_t id) const {
  auto it = thumbnails_.find(id);
  if (it == thumbnails_.end()) return cv::Mat();
  cv::Mat small = cv::imdecode(it->second.jpeg, cv::IMREAD_GRAYSCALE);
  if (small.empty() || small.size() == it->second.original) return small;
  cv::Mat full;
  cv::resize(small, full, it->second.original, 0, 0, cv::INTER_LINEAR);
  return full;
}

void KeyframeThumbnails::clear() {
  thumbnails_.clear();
  bytes_ = 0;
}

}  // namespace bowg_ros
