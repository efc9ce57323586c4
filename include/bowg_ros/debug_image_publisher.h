// The nodelet's lazy ~debug_image: the query keyframe beside its loop's match
// (or the best candidate the checks turned down), drawn by drawDebugImage
// only while somebody subscribes. It keeps what the drawing needs: the full
// images of recent keyframes while subscribed, and a thumbnail of every
// keyframe, so that the match of any loop can be shown however far back.
// Not thread-safe: the nodelet calls it under its detector lock, the lock of
// the database whose keyframe ids it stores.
#pragma once

#include <image_transport/image_transport.h>
#include <std_msgs/Header.h>

#include <cstddef>
#include <map>
#include <opencv2/core.hpp>

#include "bowg/detection/loop_detector.h"
#include "bowg_ros/keyframe_thumbnails.h"

namespace bowg_ros {

class DebugImagePublisher {
 public:
  /// `cache_size`: full keyframe images kept while subscribed (~debug_image_cache).
  DebugImagePublisher(const ThumbnailOptions& thumbnails = ThumbnailOptions(),
                      int cache_size = 200);

  /// Advertises ~debug_image on `private_transport`.
  void advertise(image_transport::ImageTransport& private_transport);

  /// Keeps the thumbnail of keyframe `result.query_id` (8-bit grey `grey`,
  /// empty for upstream features) and, while somebody subscribes, publishes
  /// its debug image stamped with `header`.
  void publish(const std_msgs::Header& header, const bowg::LoopResult& result, const cv::Mat& grey);

  /// Forgets every keyframe's image (full images and thumbnails): after a
  /// reset, a load or a new run their ids name other keyframes.
  void forgetKeyframeImages();

  /// Bytes held by the thumbnails (for the diagnostics).
  std::size_t thumbnailBytes() const { return thumbnails_.bytes(); }

 private:
  /// The image of keyframe `id`: the full one while cached, else restored
  /// from its thumbnail (`from_thumbnail` says so); empty when neither is kept.
  cv::Mat keyframeImage(bowg::EntryId id, bool* from_thumbnail) const;
  /// Keeps `grey` as keyframe `id`'s full image, at most `cache_size_` of them.
  void cache(bowg::EntryId id, const cv::Mat& grey);

  image_transport::Publisher publisher_;
  int cache_size_;
  std::map<bowg::EntryId, cv::Mat> cache_;  // full keyframe images while subscribed
  KeyframeThumbnails thumbnails_;           // every keyframe's, for the match of any loop
};

}  // namespace bowg_ros
