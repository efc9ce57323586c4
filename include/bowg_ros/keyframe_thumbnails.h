// A small JPEG thumbnail of every keyframe, so that the ~debug_image can show
// the matched place of any loop, however far back (a revisit in a pipe comes
// hundreds of keyframes later; full images of them all would cost ~77 kB
// each at 320 x 240, a thumbnail a few kB). ROS-free.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <opencv2/core.hpp>
#include <vector>

namespace bowg_ros {

struct ThumbnailOptions {
  /// Longest side of a thumbnail (px); 0 = keep none. Images no larger are
  /// kept at their size.
  int max_side = 240;
  int jpeg_quality = 80;  ///< [1, 100]
  void validate() const;  ///< throws std::invalid_argument naming the field
};

class KeyframeThumbnails {
 public:
  explicit KeyframeThumbnails(const ThumbnailOptions& options = ThumbnailOptions());

  /// Keeps a thumbnail of the 8-bit grey `image` of keyframe `id` (replaces
  /// one kept under that id). Nothing when max_side is 0 or image is empty.
  void add(std::uint32_t id, const cv::Mat& image);

  /// The image of keyframe `id` at its original size (the thumbnail scaled
  /// back up, so keypoint coordinates of the original apply), or an empty
  /// matrix when none is kept.
  cv::Mat restore(std::uint32_t id) const;

  std::size_t size() const { return thumbnails_.size(); }
  /// Bytes held by the compressed thumbnails.
  std::size_t bytes() const { return bytes_; }
  void clear();

 private:
  struct Thumbnail {
    cv::Size original;
    std::vector<std::uint8_t> jpeg;
  };
  ThumbnailOptions options_;
  std::map<std::uint32_t, Thumbnail> thumbnails_;
  std::size_t bytes_ = 0;
};

}  // namespace bowg_ros
