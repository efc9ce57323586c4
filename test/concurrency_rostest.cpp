// End-to-end test of LoopDetectorNodelet under concurrent use: live tuning,
// saving, loading and resetting through its services while its worker
// processes a stream of images. It checks what must hold whatever the
// interleaving; scripts/check_thread_sanitizer.sh runs it (with the live
// tuning and persistence tests) in a ThreadSanitizer build, which checks the
// rest. main() is loop_detector_rostest.cpp's (one test executable).
#include <nodelet/NodeletList.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "nodelet_harness.h"

namespace bowg_ros {
namespace {

// The live values a tuning client might send in turn: each changes options
// the worker reads on every keyframe (scores, word groups, the direct index
// level, verification).
BoWGConfig tuningStep(int round) {
  BoWGConfig c = BoWGConfig::__getDefault__();
  c.lambda_1 = round % 2 ? 0.5 : 0.7;
  c.lambda_2 = 0.2;
  c.min_score = round % 3 ? 0.3 : 0.6;
  c.word_groups = round % 2 == 0;
  c.temporal_score = round % 4 != 3;
  c.direct_index_level = 2 + round % 2;
  c.min_inliers = 15 + round % 3;
  return c;
}

TEST(LoopDetectorNodelet, TuningSavingLoadingAndResettingWhileProcessingKeepItConsistent) {
  Detector d("/busy", {{"debug_image_cache", 20}});
  ASSERT_TRUE(d.loaded());
  // A debug image subscriber, so the worker also renders debug images and
  // thumbnails while the services change the database under it.
  ros::NodeHandle nh;
  std::atomic<int> debug_images{0};
  ros::Subscriber debug_sub = nh.subscribe<sensor_msgs::Image>(
      d.name() + "/debug_image", 10, [&](const sensor_msgs::Image::ConstPtr&) { ++debug_images; });
  for (int i = 0; i < 100 && debug_sub.getNumPublishers() == 0; ++i)
    ros::WallDuration(0.05).sleep();

  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 9);
  const std::vector<int> xs = test::trajectory(kForward, kRevisit, kStep, kOffset);
  const std::vector<int> light = revisitBrightness();
  std::atomic<bool> streaming{true};
  std::thread camera([&] {
    for (std::size_t i = 0; i < xs.size(); ++i)
      d.publish(test::viewAt(world, xs[i], kViewWidth, light[i]), 1000.0 + 0.1 * i);
    streaming = false;
  });

  // Services from this thread while the camera streams: every call must be
  // answered and succeed (save and load of a file saved a round earlier).
  const std::string dir = BOWG_TEST_OUTPUT_DIR;
  std::vector<std::string> saved;
  int round = 0;
  while (streaming) {
    BoWGConfig c = tuningStep(round);
    EXPECT_TRUE(setConfig(d.name(), &c)) << "round " << round;
    SaveDatabase save;
    save.request.path = dir + "/bowg_busy_" + std::to_string(round % 3) + ".bin";
    ASSERT_TRUE(ros::service::call(d.name() + "/save_database", save)) << "round " << round;
    EXPECT_TRUE(save.response.success) << save.response.message;
    if (!saved.empty()) {
      LoadDatabase load;
      load.request.path = saved.back();
      ASSERT_TRUE(ros::service::call(d.name() + "/load_database", load)) << "round " << round;
      EXPECT_TRUE(load.response.success) << load.response.message;
    }
    saved.push_back(save.request.path);
    if (round % 4 == 3) {
      std_srvs::Trigger reset;
      ASSERT_TRUE(ros::service::call(d.name() + "/reset", reset)) << "round " << round;
      EXPECT_TRUE(reset.response.success);
    }
    ++round;
  }
  camera.join();
  EXPECT_GE(round, 3) << "the services ran fewer rounds than the test needs";

  // The worker is still alive and its database consistent: a frame after the
  // storm is processed, and in every database (after a reset or a load)
  // ids count from 0 without a gap, so each keyframe's database size is its
  // id + 1, whatever service ran while it was processed.
  d.publish(test::viewAt(world, 0, kViewWidth), 2000.0);
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(120);
  bool last_seen = false;
  while (!last_seen && ros::WallTime::now() < end) {
    for (const KeyframeStatus& s : d.statuses()) last_seen |= s.header.stamp.toSec() == 2000.0;
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_TRUE(last_seen) << "the frame after the storm got no keyframe status";
  const std::vector<KeyframeStatus> statuses = d.statuses();
  EXPECT_GT(statuses.size(), xs.size() / 2) << "most frames were lost";
  for (const KeyframeStatus& s : statuses)
    EXPECT_EQ(s.database_size, s.id + 1) << "keyframe at " << s.header.stamp.toSec();

  // Saving, resetting and loading once more restores exactly what was saved:
  // the next keyframe continues its ids.
  const std::uint32_t size = statuses.back().database_size;
  SaveDatabase save;
  save.request.path = dir + "/bowg_busy_final.bin";
  ASSERT_TRUE(ros::service::call(d.name() + "/save_database", save));
  ASSERT_TRUE(save.response.success) << save.response.message;
  std_srvs::Trigger reset;
  ASSERT_TRUE(ros::service::call(d.name() + "/reset", reset));
  LoadDatabase load;
  load.request.path = save.request.path;
  ASSERT_TRUE(ros::service::call(d.name() + "/load_database", load));
  ASSERT_TRUE(load.response.success) << load.response.message;
  d.clear();
  d.publish(test::viewAt(world, kStep, kViewWidth), 2001.0);
  ASSERT_TRUE(d.waitForStatuses(1, 120.0));
  EXPECT_EQ(d.statuses().back().id, size);
  EXPECT_EQ(d.statuses().back().database_size, size + 1);
  EXPECT_GT(debug_images.load(), 0) << "no debug image rendered during the storm";
}

// Unloading the nodelet while images arrive and a client calls its services:
// callbacks are still running at the unload (the manager then destroys the
// nodelet from the callback's thread, after its queues). The manager must
// survive every round and load the nodelet again. Under ThreadSanitizer
// (scripts/check_thread_sanitizer.sh) a handle shut down on a destroyed
// queue is reported.
TEST(LoopDetectorNodelet, UnloadingWhileProcessingAndServingLeavesTheManagerWorking) {
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 9);
  const std::string dir = BOWG_TEST_OUTPUT_DIR;
  for (int round = 0; round < 4; ++round) {
    Detector d("/unload" + std::to_string(round), {});
    ASSERT_TRUE(d.loaded()) << "round " << round;
    std::atomic<bool> running{true};
    std::thread client([&] {
      // Fails once the nodelet is gone: only the calls' overlap matters.
      for (int i = 0; running; ++i) {
        SaveDatabase save;
        save.request.path = dir + "/bowg_unload.bin";
        ros::service::call(d.name() + "/save_database", save);
        std_srvs::Trigger reset;
        if (i % 2) ros::service::call(d.name() + "/reset", reset);
      }
    });
    for (int i = 0; i < 8 + 3 * round; ++i)
      d.publish(test::viewAt(world, i * kStep, kViewWidth), 1000.0 + 0.1 * i);
    EXPECT_TRUE(d.unload()) << "round " << round;
    running = false;
    client.join();

    nodelet::NodeletList list;
    ASSERT_TRUE(ros::service::call("/bowg_manager/list", list))
        << "the manager died in round " << round;
    EXPECT_EQ(std::count(list.response.nodelets.begin(), list.response.nodelets.end(), d.name()), 0)
        << "round " << round;
  }
  // The manager loads and runs the nodelet once more.
  Detector d("/unload_after", {});
  ASSERT_TRUE(d.loaded());
  d.publish(test::viewAt(world, 0, kViewWidth), 2000.0);
  EXPECT_TRUE(d.waitForStatuses(1, 60.0));
}

}  // namespace
}  // namespace bowg_ros
