// End-to-end tests of the nodelet's /diagnostics: each way it can fail to
// turn frames into keyframes gives the level and the reason a robot's
// monitoring needs (test/diagnostics.test).
#include <nav_msgs/Odometry.h>
#include <std_msgs/Float64.h>

#include <string>

#include "bowg_ros/OdometerStamped.h"
#include "nodelet_harness.h"

namespace bowg_ros {
namespace {

using diagnostic_msgs::DiagnosticStatus;

TEST(Diagnostics, AFailedImageSubscriptionIsAnErrorNamingTheTopic) {
  DiagnosticsWatcher diagnostics;
  // No image_transport plugin has this name: the subscription throws.
  Detector d("/noinput", {{"image_transport", XmlRpc::XmlRpcValue("no_such_transport")}});
  ASSERT_TRUE(d.loaded());
  EXPECT_FALSE(d.connected());
  DiagnosticStatus last;
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::ERROR,
                                  "no input: cannot subscribe to /noinput/image", 10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
}

// A nodelet that cannot start (here: its vocabulary file is missing) says
// why in its diagnostics, an ERROR for as long as it is loaded.
TEST(Diagnostics, AStartUpFailureIsAnErrorSayingWhy) {
  DiagnosticsWatcher diagnostics;
  Detector d("/novocabulary",
             {{"vocabulary_path", XmlRpc::XmlRpcValue("/nonexistent/vocabulary.bowgvoc")}});
  ASSERT_TRUE(d.loaded());
  EXPECT_FALSE(d.connected());
  DiagnosticStatus last;
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::ERROR, "not started: ", 10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  EXPECT_NE(last.message.find("/nonexistent/vocabulary.bowgvoc"), std::string::npos)
      << last.message;
}

TEST(Diagnostics, ADistanceGateWithoutOdometryWarnsUntilOdometryArrives) {
  DiagnosticsWatcher diagnostics;
  Detector d("/nodistance", {{"min_keyframe_distance", XmlRpc::XmlRpcValue(0.5)}});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 5);
  d.publish(test::viewAt(world, 0, kViewWidth), 100.0);
  d.publish(test::viewAt(world, kStep, kViewWidth), 100.1);
  // Without odometry only the time gate applies: both frames are keyframes.
  ASSERT_TRUE(d.waitForStatuses(2, 20.0));
  DiagnosticStatus last;
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::WARN,
                                  "no odometry arrived on /nodistance/odom", 10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  EXPECT_EQ(diagnostics.value(d.name(), "odometry received"), "False");
  ros::NodeHandle nh;
  ros::Publisher odom = nh.advertise<nav_msgs::Odometry>("/nodistance/odom", 10);
  for (int i = 0; i < 100 && odom.getNumSubscribers() == 0; ++i) ros::WallDuration(0.05).sleep();
  nav_msgs::Odometry o;
  o.header.stamp = ros::Time(100.15);
  odom.publish(o);
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::OK, "running", 10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
}

// A stamped odometer (odometer_stamped): a frame gets the reading at its
// stamp even when the image is handled first, and one whose reading never
// comes goes on after ~odometry_wait, counted. Seen through the distance
// gate: 0.5 m between keyframes.
TEST(Diagnostics, AFrameWaitsForTheStampedOdometerReadingAtItsStamp) {
  DiagnosticsWatcher diagnostics;
  Detector d("/stamped", {{"min_keyframe_distance", XmlRpc::XmlRpcValue(0.5)},
                          {"odometry_wait", XmlRpc::XmlRpcValue(0.3)}});
  ASSERT_TRUE(d.loaded());
  ros::NodeHandle nh;
  ros::Publisher stamped = nh.advertise<OdometerStamped>("/stamped/odometer_stamped", 10);
  ros::Publisher unstamped = nh.advertise<std_msgs::Float64>("/stamped/odometer", 10);
  for (int i = 0;
       i < 100 && (stamped.getNumSubscribers() == 0 || unstamped.getNumSubscribers() == 0); ++i) {
    ros::WallDuration(0.05).sleep();
  }
  const auto reading = [&](double stamp, double metres) {
    OdometerStamped r;
    r.header.stamp = ros::Time(stamp);
    r.metres = metres;
    stamped.publish(r);
  };
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 5);
  reading(100.0, 0.0);
  ros::WallDuration(0.1).sleep();
  d.publish(test::viewAt(world, 0, kViewWidth), 100.0);  // the first keyframe
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  // The image of 100.1 before its reading (1 m further): it waits for it and
  // is a keyframe. Taken on arrival, it would have had 0 m: too close.
  d.publish(test::viewAt(world, kStep, kViewWidth), 100.1);
  ros::WallDuration(0.1).sleep();
  reading(100.1, 1.0);
  ASSERT_TRUE(d.waitForStatuses(2, 20.0));
  // The unstamped topic is ignored now: 5 m on it change nothing.
  std_msgs::Float64 far;
  far.data = 5.0;
  unstamped.publish(far);
  ros::WallDuration(0.1).sleep();
  // No reading for 100.2: after 0.3 s it goes on with 1 m, 0 m from the last
  // keyframe: too close, and counted.
  d.publish(test::viewAt(world, 2 * kStep, kViewWidth), 100.2);
  DiagnosticStatus last;
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::WARN,
                                  "1 frames went on without the odometry at their stamp on "
                                  "/stamped/odom or /stamped/odometer_stamped",
                                  10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  EXPECT_EQ(diagnostics.value(d.name(), "frames without the odometry at their stamp"), "1");
  EXPECT_EQ(diagnostics.value(d.name(), "frames received"), "3");
  EXPECT_EQ(d.statuses().size(), 2u);
}

// Odometry positions (odom) by their stamps too: a frame gets the position
// at its stamp even when the image is handled first, and one whose position
// never comes goes on after ~odometry_wait, counted. Through the distance
// gate: 0.5 m between keyframes.
TEST(Diagnostics, AFrameWaitsForTheOdometryPositionAtItsStamp) {
  DiagnosticsWatcher diagnostics;
  Detector d("/stampedodom", {{"min_keyframe_distance", XmlRpc::XmlRpcValue(0.5)},
                              {"odometry_wait", XmlRpc::XmlRpcValue(0.3)}});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 5);
  d.publishOdometry(cv::Point3d(0, 0, 0), 100.0);
  d.publish(test::viewAt(world, 0, kViewWidth), 100.0);  // the first keyframe
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  // The image of 100.1 before its position (1 m further): it waits for it
  // and is a keyframe. Taken on arrival, it would have had 0 m: too close.
  d.publish(test::viewAt(world, kStep, kViewWidth), 100.1);
  ros::WallDuration(0.1).sleep();
  d.publishOdometry(cv::Point3d(1, 0, 0), 100.1);
  ASSERT_TRUE(d.waitForStatuses(2, 20.0));
  // A position stamped after the next image (another 1 m) stays after it:
  // the image of 100.2 has 0 m since the last keyframe, too close.
  d.publish(test::viewAt(world, 2 * kStep, kViewWidth), 100.2);
  ros::WallDuration(0.1).sleep();
  d.publishOdometry(cv::Point3d(2, 0, 0), 100.25);
  // No position for 100.3 (the last came at 100.25): it goes on after
  // 0.3 s with the 1 m since the last keyframe: a keyframe, counted.
  d.publish(test::viewAt(world, 3 * kStep, kViewWidth), 100.3);
  DiagnosticStatus last;
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::WARN,
                                  "1 frames went on without the odometry at their stamp on "
                                  "/stampedodom/odom or /stampedodom/odometer_stamped",
                                  10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  EXPECT_EQ(diagnostics.value(d.name(), "frames without the odometry at their stamp"), "1");
  EXPECT_EQ(diagnostics.value(d.name(), "frames received"), "4");
  ASSERT_TRUE(d.waitForStatuses(3, 20.0));
  const std::vector<KeyframeStatus> statuses = d.statuses();
  ASSERT_EQ(statuses.size(), 3u);
  EXPECT_DOUBLE_EQ(statuses[2].header.stamp.toSec(), 100.3);
}

// Bad frames on the compressed topic are refused from their header before
// decoding (a PNG declaring 30000 x 30000 pixels would take 900 MB) and
// counted by the reason the offline tools give; the nodelet goes on.
TEST(Diagnostics, BadCompressedFramesAreCountedByReason) {
  DiagnosticsWatcher diagnostics;
  Detector d("/badcompressed", {{"use_compressed", XmlRpc::XmlRpcValue(true)}});
  ASSERT_TRUE(d.loaded());
  d.publishCompressed(bowg::test::truncatedJpeg(), 200.0);
  d.publishCompressed(bowg::test::pngDeclaring(30000, 30000), 200.1);
  d.publishCompressed({}, 200.2);
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 5);
  d.publishCompressed(bowg::test::encodeImage(test::viewAt(world, 0, kViewWidth), ".png"), 200.3);
  EXPECT_TRUE(d.waitForStatuses(1, 20.0)) << "the good frame after the bad ones";
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(15.0);
  const auto count = [&](const char* reason) {
    return diagnostics.value(d.name(), std::string("dropped images (") + reason + ")");
  };
  while (ros::WallTime::now() < end &&
         !(count("truncated") == "1" && count("too_large") == "1" && count("empty") == "1")) {
    ros::WallDuration(0.1).sleep();
  }
  EXPECT_EQ(count("truncated"), "1");
  EXPECT_EQ(count("too_large"), "1");
  EXPECT_EQ(count("empty"), "1");
  EXPECT_EQ(count("undecodable"), "0");
  EXPECT_EQ(diagnostics.value(d.name(), "keyframe errors"), "0");
}

// Silence on the image topic (a wrong topic, a compressed stream read as
// raw) is a warning within the diagnostics window, naming the topic, and
// saying what a camera_info arriving alone means; it clears when images come.
TEST(Diagnostics, NoImageIsAWarningNamingTheTopicThatClearsWhenImagesCome) {
  DiagnosticsWatcher diagnostics;
  Detector d("/silent", {{"diagnostics_window", XmlRpc::XmlRpcValue(2.0)}});
  ASSERT_TRUE(d.loaded());
  DiagnosticStatus last;
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::WARN, "no image on /silent/image for",
                                  10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  EXPECT_EQ(last.message.find("camera_info"), std::string::npos) << last.message;
  // A camera whose images go elsewhere (a compressed stream): camera_info alone.
  d.publishCameraInfo(100.0);
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::WARN,
                                  "camera_info arrives on /silent/camera_info: a compressed "
                                  "stream? set ~use_compressed",
                                  10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  const cv::Mat world = test::makeWorld(kViewWidth + 40 * kStep, kViewHeight, 8);
  bool running = false;
  for (int i = 0; i < 30 && !running; ++i) {
    d.publish(test::viewAt(world, i * kStep, kViewWidth), 101.0 + 0.1 * i);
    running = diagnostics.waitFor(d.name(), DiagnosticStatus::OK, "running", 0.3, &last);
  }
  EXPECT_TRUE(running) << "level " << int(last.level) << ": " << last.message;
}

// A warning says what happened within the window and clears after it: one
// frame of an unsupported encoding, then good frames for longer than the
// window.
TEST(Diagnostics, AWarningClearsWhenItsCauseStopsForTheWindow) {
  DiagnosticsWatcher diagnostics;
  Detector d("/clears", {{"diagnostics_window", XmlRpc::XmlRpcValue(2.0)}});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kViewWidth + 80 * kStep, kViewHeight, 9);
  d.publish(test::viewAt(world, 0, kViewWidth), 100.0);
  sensor_msgs::Image bad;
  bad.header.stamp = ros::Time(100.1);
  bad.encoding = "yuv422";
  bad.width = 2;
  bad.height = 2;
  bad.step = 4;
  bad.data.resize(8);
  d.publishRaw(bad);
  DiagnosticStatus last;
  ASSERT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::WARN,
                                  "frames rejected in the last 2 s", 10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  // Good frames for more than the window: back to OK, the count kept.
  bool running = false;
  for (int i = 1; i < 70 && !running; ++i) {
    d.publish(test::viewAt(world, i * kStep, kViewWidth), 100.1 + 0.1 * i);
    running = diagnostics.waitFor(d.name(), DiagnosticStatus::OK, "running", 0.1, &last);
  }
  EXPECT_TRUE(running) << "level " << int(last.level) << ": " << last.message;
  EXPECT_EQ(diagnostics.value(d.name(), "dropped images (unsupported_format)"), "1");
}

TEST(Diagnostics, StampsGoingBackAreAWarningThatSaysWhatToDo) {
  DiagnosticsWatcher diagnostics;
  Detector d("/replay", {});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 6);
  d.publish(test::viewAt(world, 0, kViewWidth), 100.0);
  d.publish(test::viewAt(world, kStep, kViewWidth), 100.1);
  ASSERT_TRUE(d.waitForStatuses(2, 20.0));
  DiagnosticStatus last;
  ASSERT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::OK, "running", 10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  // The bag starts over.
  d.publish(test::viewAt(world, 0, kViewWidth), 50.0);
  EXPECT_TRUE(diagnostics.waitFor(d.name(), DiagnosticStatus::WARN,
                                  "1 frames skipped for their stamps (latest: frame at "
                                  "50.000000 s: stamp older than the previous frame); a replay "
                                  "that starts over needs ~reset or ~reset_on_time_jump",
                                  10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  ros::WallDuration(0.3).sleep();
  EXPECT_EQ(d.statusCount(), 2u);
}

TEST(Diagnostics, WithResetOnTimeJumpAReplayThatStartsOverStartsANewDatabase) {
  DiagnosticsWatcher diagnostics;
  Detector d("/restart", {{"reset_on_time_jump", XmlRpc::XmlRpcValue(5.0)}});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 7);
  for (int i = 0; i < 4; ++i)
    d.publish(test::viewAt(world, i * kStep, kViewWidth), 100.0 + 0.1 * i);
  // 2 s back: out of order, not a new run.
  d.publish(test::viewAt(world, 0, kViewWidth), 98.3);
  // 90 s back: a new run.
  for (int i = 0; i < 3; ++i) d.publish(test::viewAt(world, i * kStep, kViewWidth), 10.0 + 0.1 * i);
  ASSERT_TRUE(d.waitForStatuses(7, 20.0));
  ros::WallDuration(0.3).sleep();
  const std::vector<KeyframeStatus> s = d.statuses();
  ASSERT_EQ(s.size(), 7u);
  EXPECT_EQ(s[3].database_size, 4u);
  EXPECT_DOUBLE_EQ(s[4].header.stamp.toSec(), 10.0);
  EXPECT_EQ(s[4].id, 0u);  // the new run's first keyframe
  EXPECT_EQ(s[4].database_size, 1u);
  EXPECT_EQ(s[6].database_size, 3u);
  DiagnosticStatus last;
  EXPECT_TRUE(
      diagnostics.waitFor(d.name(), DiagnosticStatus::WARN, "1 frames skipped", 10.0, &last))
      << "level " << int(last.level) << ": " << last.message;
  EXPECT_EQ(diagnostics.value(d.name(), "new runs (time jumped back)"), "1");
}

}  // namespace
}  // namespace bowg_ros
