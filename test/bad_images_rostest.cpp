// End-to-end tests of LoopDetectorNodelet on images it cannot use
// (malformed, oversize, of an unsupported encoding): each is reported,
// counted and dropped, and the nodelet keeps running. The harness is
// nodelet_harness.h and main() is loop_detector_rostest.cpp's (one test
// executable).
#include <diagnostic_msgs/DiagnosticArray.h>

#include <atomic>
#include <mutex>
#include <set>
#include <string>

#include "nodelet_harness.h"

namespace bowg_ros {
namespace {

TEST(LoopDetectorNodelet, MalformedImagesAreReportedAndTheNodeletKeepsRunning) {
  ErrorLog log;
  Detector d("/malformed", {});
  ASSERT_TRUE(d.loaded());
  ros::WallDuration(0.5).sleep();  // /rosout connection
  // mono8, 64 x 48, step 64, but only 100 bytes of data: a reader of
  // height x step bytes would run past the buffer.
  sensor_msgs::Image bad;
  bad.header.stamp = ros::Time(500.0);
  bad.header.frame_id = kFrame;
  bad.width = 64;
  bad.height = 48;
  bad.step = 64;
  bad.encoding = "mono8";
  bad.data.assign(100, 0);
  d.publishRaw(bad);
  EXPECT_TRUE(log.waitFor("image at 500.000000 dropped: malformed: ", 10.0))
      << "no error for the image";
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 3);
  d.publish(test::viewAt(world, 0, kViewWidth), 501.0);
  EXPECT_TRUE(d.waitForStatuses(1, 20.0)) << "the nodelet stopped after a malformed image";
}

TEST(LoopDetectorNodelet, OversizeImagesAreDroppedCountedAndTheNodeletKeepsRunning) {
  ErrorLog log;
  // The diagnostics' count of images above max_image_pixels.
  std::atomic<int> too_large{-1};
  std::mutex names_mutex;
  std::set<std::string> names;  // for the failure message
  ros::NodeHandle nh;
  const ros::Subscriber diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 20, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
        for (const auto& st : msg->status) {
          {
            std::lock_guard<std::mutex> lock(names_mutex);
            names.insert(st.name);
          }
          if (st.name.find("oversize/bowg") == std::string::npos) continue;
          for (const auto& kv : st.values) {
            if (kv.key == "dropped images (too_large)") {
              too_large = std::stoi(kv.value);
            }
          }
        }
      });
  // The views are 320 x 240 = 76,800 pixels: one pixel more than allowed.
  Detector d("/oversize", {{"max_image_pixels", kViewWidth * kViewHeight - 1}});
  ASSERT_TRUE(d.loaded());
  ros::WallDuration(0.5).sleep();  // /rosout connection
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 3);
  d.publish(test::viewAt(world, 0, kViewWidth), 700.0);
  EXPECT_TRUE(
      log.waitFor("image at 700.000000 dropped: too_large: 320 x 240 = 76800 pixels, more "
                  "than max_image_pixels 76799",
                  10.0))
      << "no error for the image";
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);
  while (too_large != 1 && ros::WallTime::now() < end) ros::WallDuration(0.1).sleep();
  {
    std::lock_guard<std::mutex> lock(names_mutex);
    std::string seen;
    for (const std::string& n : names) seen += " '" + n + "'";
    EXPECT_EQ(too_large, 1) << "the diagnostics do not count the dropped image; statuses:" << seen;
  }
  // Still alive: a smaller image is processed.
  d.publish(test::viewAt(world, 0, kViewWidth).rowRange(0, kViewHeight - 1).clone(), 701.0);
  EXPECT_TRUE(d.waitForStatuses(1, 20.0)) << "the nodelet stopped after a too large image";
  EXPECT_EQ(d.statusCount(), 1u);
}

TEST(LoopDetectorNodelet, UnsupportedEncodingIsReportedAndTheNodeletKeepsRunning) {
  ErrorLog log;
  Detector d("/encoding", {});
  ASSERT_TRUE(d.loaded());
  ros::WallDuration(0.5).sleep();  // /rosout connection
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 3);
  cv::Mat depth(kViewHeight, kViewWidth, CV_32FC1, cv::Scalar(1.5f));
  d.publish(depth, 999.0, "32FC1");
  EXPECT_TRUE(log.waitFor("'32FC1'", 10.0)) << "no error naming the encoding";
  // Still alive: every supported encoding gives a keyframe status.
  const cv::Mat view = test::viewAt(world, 0, kViewWidth);
  cv::Mat bgr, rgba, mono16;
  cv::cvtColor(view, bgr, cv::COLOR_GRAY2BGR);
  cv::cvtColor(view, rgba, cv::COLOR_GRAY2RGBA);
  view.convertTo(mono16, CV_16U, 256.0);
  d.publish(view, 1000.0, "mono8");
  d.publish(mono16, 1000.1, "mono16");
  d.publish(bgr, 1000.2, "bgr8");
  d.publish(bgr, 1000.3, "rgb8");
  d.publish(rgba, 1000.4, "rgba8");
  d.publish(rgba, 1000.5, "bgra8");
  ASSERT_TRUE(d.waitForStatuses(6, 20.0));
  const std::vector<KeyframeStatus> s = d.statuses();
  ASSERT_EQ(s.size(), 6u);
  // The grey conversions agree up to rounding, so the features do too.
  for (const KeyframeStatus& k : s) {
    EXPECT_NEAR(static_cast<double>(k.num_features), s[0].num_features, 0.1 * s[0].num_features);
  }
  // A repeated and an older stamp are skipped (no status).
  d.publish(view, 1000.5, "mono8");
  d.publish(view, 900.0, "mono8");
  d.publish(view, 1001.0, "mono8");
  ASSERT_TRUE(d.waitForStatuses(7, 20.0));
  ros::WallDuration(0.3).sleep();
  EXPECT_EQ(d.statusCount(), 7u);
  EXPECT_DOUBLE_EQ(d.statuses().back().header.stamp.toSec(), 1001.0);
}

}  // namespace
}  // namespace bowg_ros
