// DebugImagePublisher: the lazy ~debug_image and the keyframe images it shows.
#include "bowg_ros/debug_image_publisher.h"

#include <cv_bridge/cv_bridge.h>

#include <cstdio>
#include <string>
#include <vector>

#include "bowg_ros/debug_image.h"

namespace bowg_ros {
namespace {

/// "keyframe 12: loop detected -> 3, 40 inliers\n(score ...)" and, when the
/// match comes from a thumbnail, a note saying so.
std::string captionOf(const bowg::LoopResult& result, bool from_thumbnail) {
  const bool found = result.status == bowg::LoopStatus::kLoopDetected;
  char scores[96] = "";
  if (result.has_candidate) {
    std::snprintf(scores, sizeof scores, " (score %.3f, island %u-%u)", result.best.eta,
                  result.island_first, result.island_last);
  }
  std::string caption =
      "keyframe " + std::to_string(result.query_id) + ": " + bowg::toString(result.status);
  if (found) {
    caption += " -> " + std::to_string(result.match_id) + ", " + std::to_string(result.inliers) +
               " inliers";
  } else if (result.has_candidate) {
    caption += "; best candidate " + std::to_string(result.best.entry);
  }
  caption += std::string("\n") + (result.has_candidate ? scores + 1 : "no candidate");
  if (from_thumbnail) caption += "; match shown from its thumbnail";
  return caption;
}

}  // namespace

DebugImagePublisher::DebugImagePublisher(const ThumbnailOptions& thumbnails, int cache_size)
    : cache_size_(cache_size), thumbnails_(thumbnails) {}

void DebugImagePublisher::advertise(image_transport::ImageTransport& private_transport) {
  publisher_ = private_transport.advertise("debug_image", 1);
}

void DebugImagePublisher::forgetKeyframeImages() {
  cache_.clear();
  thumbnails_.clear();
}

cv::Mat DebugImagePublisher::keyframeImage(bowg::EntryId id, bool* from_thumbnail) const {
  *from_thumbnail = false;
  auto it = cache_.find(id);
  if (it != cache_.end()) return it->second;
  cv::Mat image = thumbnails_.restore(id);
  *from_thumbnail = !image.empty();
  return image;
}

void DebugImagePublisher::cache(bowg::EntryId id, const cv::Mat& grey) {
  // A mono8 grey image shares the message buffer, which cv_bridge does not
  // keep alive beyond the frame: the cache holds its own copy.
  cache_[id] = grey.clone();
  while (static_cast<int>(cache_.size()) > cache_size_) cache_.erase(cache_.begin());
}

void DebugImagePublisher::publish(const std_msgs::Header& header, const bowg::LoopResult& result,
                                  const cv::Mat& grey) {
  // Every keyframe leaves a thumbnail, so that the debug image can show the
  // matched place of any loop (a revisit comes hundreds of keyframes later).
  thumbnails_.add(result.query_id, grey);

  // Lazy: the debug image is drawn, and full images are cached, only while
  // somebody subscribes.
  if (publisher_.getNumSubscribers() == 0 || grey.empty()) {
    cache_.clear();
    return;
  }
  // The loop's match, or else the best candidate the checks turned down.
  const bool found = result.status == bowg::LoopStatus::kLoopDetected;
  cv::Mat match;
  bool from_thumbnail = false;
  if (found || result.has_candidate) {
    match = keyframeImage(found ? result.match_id : result.best.entry, &from_thumbnail);
  }
  cv_bridge::CvImage out(
      header, "bgr8",
      drawDebugImage(grey, match,
                     found ? result.inlier_correspondences : std::vector<bowg::Correspondence>(),
                     captionOf(result, from_thumbnail)));
  publisher_.publish(out.toImageMsg());
  cache(result.query_id, grey);
}

}  // namespace bowg_ros
