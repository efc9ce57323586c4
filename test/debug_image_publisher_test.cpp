// DebugImagePublisher without a subscriber (no master): what it keeps of
// each keyframe for the debug image of a later loop, and what it forgets.
// The drawing while subscribed is checked end to end by
// loop_detector_rostest.cpp (the debug images, a match from its thumbnail).
#include "bowg_ros/debug_image_publisher.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace bowg_ros {
namespace {

cv::Mat noise(int seed) {
  cv::Mat m(240, 320, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0, 255);
  return m;
}

bowg::LoopResult keyframe(bowg::EntryId id) {
  bowg::LoopResult r;
  r.query_id = id;
  r.status = bowg::LoopStatus::kDatabaseTooSmall;
  return r;
}

TEST(DebugImagePublisher, EveryKeyframeLeavesAThumbnailWithoutASubscriber) {
  DebugImagePublisher debug;  // never advertised: nobody subscribes
  EXPECT_EQ(debug.thumbnailBytes(), 0u);
  debug.publish(std_msgs::Header(), keyframe(0), noise(1));
  const std::size_t one = debug.thumbnailBytes();
  EXPECT_GT(one, 0u);
  debug.publish(std_msgs::Header(), keyframe(1), noise(2));
  EXPECT_GT(debug.thumbnailBytes(), one);
}

TEST(DebugImagePublisher, UpstreamFeaturesLeaveNoThumbnail) {
  DebugImagePublisher debug;
  debug.publish(std_msgs::Header(), keyframe(0), cv::Mat());  // keyframe_features: no image
  EXPECT_EQ(debug.thumbnailBytes(), 0u);
}

TEST(DebugImagePublisher, ForgetsEveryKeyframeImage) {
  DebugImagePublisher debug;
  for (bowg::EntryId id = 0; id < 3; ++id) {
    debug.publish(std_msgs::Header(), keyframe(id), noise(static_cast<int>(id)));
  }
  ASSERT_GT(debug.thumbnailBytes(), 0u);
  debug.forgetKeyframeImages();
  EXPECT_EQ(debug.thumbnailBytes(), 0u);
}

TEST(DebugImagePublisher, ThumbnailsOffKeepNone) {
  ThumbnailOptions off;
  off.max_side = 0;
  DebugImagePublisher debug(off, 5);
  debug.publish(std_msgs::Header(), keyframe(0), noise(1));
  EXPECT_EQ(debug.thumbnailBytes(), 0u);
}

TEST(DebugImagePublisher, RefusesInvalidThumbnailOptions) {
  ThumbnailOptions bad;
  bad.jpeg_quality = 0;  // the nodelet reports this as why it does not start
  EXPECT_THROW(DebugImagePublisher(bad, 5), std::invalid_argument);
}

}  // namespace
}  // namespace bowg_ros
