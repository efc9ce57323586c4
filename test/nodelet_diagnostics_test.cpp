// NodeletDiagnostics: events in, the "loop detector" status out (level,
// message, values), on a clock the test moves.
#include "bowg_ros/nodelet_diagnostics.h"

#include <gtest/gtest.h>

#include <string>

namespace bowg_ros {
namespace {

using Clock = NodeletDiagnostics::Clock;
using diagnostic_msgs::DiagnosticStatus;

class NodeletDiagnosticsTest : public ::testing::Test {
 protected:
  NodeletDiagnosticsTest() : diagnostics([this] { return now; }) {
    settings.image_topic = "/cam/image";
    settings.features_topic = "/cam/keyframe_features";
    settings.camera_info_topic = "/cam/camera_info";
    settings.odom_topic = "/cam/odom";
    settings.odometer_topic = "/cam/odometer";
    settings.odometer_stamped_topic = "/cam/odometer_stamped";
    settings.window = 30.0;
    diagnostics.configure(settings);
    nodelet.started = true;
  }

  void advance(double seconds) {
    now += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  }

  diagnostic_updater::DiagnosticStatusWrapper diagnose() {
    diagnostic_updater::DiagnosticStatusWrapper status;
    diagnostics.diagnose(status, nodelet);
    return status;
  }

  /// The value under `key`, or "<missing>".
  static std::string value(const diagnostic_updater::DiagnosticStatusWrapper& status,
                           const std::string& key) {
    for (const auto& kv : status.values) {
      if (kv.key == key) return kv.value;
    }
    return "<missing>";
  }

  // Far from the clock's epoch, as a steady clock is after boot.
  Clock::time_point now = Clock::time_point() + std::chrono::hours(1);
  DiagnosticsSettings settings;
  NodeletSnapshot nodelet;
  NodeletDiagnostics diagnostics;
};

bowg::LoopResult loopResult(bool found) {
  bowg::LoopResult r;
  r.status = found ? bowg::LoopStatus::kLoopDetected : bowg::LoopStatus::kNoCandidates;
  r.timings.transform_ms = 1.0;
  r.timings.query_ms = 2.0;
  r.timings.total_ms = 5.0;
  return r;
}

TEST_F(NodeletDiagnosticsTest, AFreshRunningNodeletIsOkWithEveryValueAtZero) {
  nodelet.database_size = 7;
  const auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::OK);
  EXPECT_EQ(status.message, "running");
  EXPECT_EQ(value(status, "frames received"), "0");
  EXPECT_EQ(value(status, "database size"), "7");
  EXPECT_EQ(value(status, "dropped images (truncated)"), "0");
  EXPECT_EQ(value(status, "odometry input"), "none (images only)");
  EXPECT_EQ(value(status, "camera intrinsics known"), "False");
  EXPECT_EQ(value(status, "last stamp-order skip"), "<missing>");
}

TEST_F(NodeletDiagnosticsTest, ANodeletThatDidNotStartIsAnErrorSayingWhy) {
  nodelet.started = false;
  nodelet.startup_error = "~vocabulary_path is not set";
  advance(100);  // no silence warning for a nodelet that never started
  const auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::ERROR);
  EXPECT_EQ(status.message, "not started: ~vocabulary_path is not set");
  nodelet.startup_error.clear();
  EXPECT_EQ(diagnose().message, "not started (see the log)");
}

TEST_F(NodeletDiagnosticsTest, AnInputProblemIsAnErrorThatOutranksWarnings) {
  diagnostics.frameReceived(1.0, GateDecision::kAccept);
  diagnostics.frameReceived(0.5, GateDecision::kOutOfOrder);  // a warning
  diagnostics.inputProblem("cannot subscribe to /cam/image: no plugin");
  const auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::ERROR);
  EXPECT_EQ(status.message, "no input: cannot subscribe to /cam/image: no plugin");
}

TEST_F(NodeletDiagnosticsTest, SilenceLongerThanTheWindowWarnsNamingTheTopic) {
  advance(29);
  EXPECT_EQ(diagnose().level, DiagnosticStatus::OK);
  advance(2);
  auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::WARN);
  EXPECT_EQ(status.message, "no image on /cam/image for 31 s");
  diagnostics.cameraInfoReceived();
  EXPECT_EQ(diagnose().message,
            "no image on /cam/image for 31 s; camera_info arrives on /cam/camera_info: a "
            "compressed stream? set ~use_compressed");
  diagnostics.frameReceived(1.0, GateDecision::kAccept);
  EXPECT_EQ(diagnose().level, DiagnosticStatus::OK);
}

TEST_F(NodeletDiagnosticsTest, SilenceNamesTheTopicOfTheInputMode) {
  settings.input = DiagnosticsSettings::Input::kCompressed;
  diagnostics.configure(settings);
  diagnostics.cameraInfoReceived();
  advance(40);
  diagnostics.cameraInfoReceived();
  EXPECT_EQ(diagnose().message,
            "no image on /cam/image/compressed for 40 s; camera_info arrives on "
            "/cam/camera_info: is the image topic right?");
  settings.input = DiagnosticsSettings::Input::kFeatures;
  diagnostics.configure(settings);
  EXPECT_EQ(diagnose().message, "no keyframe features on /cam/keyframe_features for 40 s");
}

TEST_F(NodeletDiagnosticsTest, StampSkipsWarnWhileRecentAndStayCounted) {
  diagnostics.frameReceived(100.0, GateDecision::kAccept);
  diagnostics.frameReceived(50.0, GateDecision::kOutOfOrder);
  auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::WARN);
  EXPECT_EQ(status.message,
            "1 frames skipped for their stamps (latest: frame at 50.000000 s: stamp older than "
            "the previous frame); a replay that starts over needs ~reset or ~reset_on_time_jump");
  EXPECT_EQ(value(status, "frames received"), "2");
  EXPECT_EQ(value(status, "skipped frames (stamp order)"), "1");
  EXPECT_EQ(value(status, "last stamp-order skip"),
            "frame at 50.000000 s: stamp older than the previous frame");
  advance(31);
  diagnostics.frameReceived(101.0, GateDecision::kAccept);
  status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::OK) << status.message;
  EXPECT_EQ(value(status, "skipped frames (stamp order)"), "1");
}

TEST_F(NodeletDiagnosticsTest, FramesWithoutTheirOdometerReadingWarnWhileRecent) {
  EXPECT_EQ(value(diagnose(), "frames without the odometry at their stamp"), "0");
  diagnostics.frameReceived(100.0, GateDecision::kAccept);
  diagnostics.odometryLate();
  diagnostics.odometryLate();
  auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::WARN);
  EXPECT_EQ(status.message,
            "2 frames went on without the odometry at their stamp on /cam/odom or "
            "/cam/odometer_stamped "
            "(waited ~odometry_wait): the readings come late, stopped, or are stamped on another "
            "clock than the images");
  EXPECT_EQ(value(status, "frames without the odometry at their stamp"), "2");
  advance(31);
  diagnostics.frameReceived(101.0, GateDecision::kAccept);
  status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::OK) << status.message;
  EXPECT_EQ(value(status, "frames without the odometry at their stamp"), "2");
}

TEST_F(NodeletDiagnosticsTest, ATimeJumpCountsANewRunWithoutAWarning) {
  diagnostics.frameReceived(100.0, GateDecision::kAccept);
  diagnostics.frameReceived(1.0, GateDecision::kTimeJump);
  const auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::OK);
  EXPECT_EQ(value(status, "new runs (time jumped back)"), "1");
  EXPECT_EQ(value(status, "skipped frames (stamp order)"), "0");
}

TEST_F(NodeletDiagnosticsTest, BadImagesAreCountedByReasonAndLoggedEachReasonEvery5s) {
  EXPECT_TRUE(diagnostics.badImage(bowg::ImageProblem::kTruncated));
  EXPECT_FALSE(diagnostics.badImage(bowg::ImageProblem::kTruncated));
  EXPECT_TRUE(diagnostics.badImage(bowg::ImageProblem::kTooLarge)) << "another reason";
  advance(5);
  EXPECT_TRUE(diagnostics.badImage(bowg::ImageProblem::kTruncated));
  auto status = diagnose();
  EXPECT_EQ(value(status, "dropped images (truncated)"), "3");
  EXPECT_EQ(value(status, "dropped images (too_large)"), "1");
  EXPECT_EQ(value(status, "dropped images (empty)"), "0");
  EXPECT_EQ(value(status, "frames received"), "0") << "a refused image is not received";
  EXPECT_EQ(status.level, DiagnosticStatus::WARN);
  EXPECT_EQ(status.message,
            "frames rejected in the last 30 s (bad images: see \"dropped images (...)\", or "
            "processing errors)");
  advance(31);
  diagnostics.frameReceived(1.0, GateDecision::kAccept);
  EXPECT_EQ(diagnose().level, DiagnosticStatus::OK);
}

TEST_F(NodeletDiagnosticsTest, KeyframeErrorsAreRejectedFrames) {
  diagnostics.frameReceived(1.0, GateDecision::kAccept);
  diagnostics.keyframeError();
  const auto status = diagnose();
  EXPECT_EQ(value(status, "keyframe errors"), "1");
  EXPECT_EQ(status.level, DiagnosticStatus::WARN);
  EXPECT_EQ(status.message.compare(0, 30, "frames rejected in the last 30"), 0) << status.message;
}

TEST_F(NodeletDiagnosticsTest, KeyframesCountLoopsAndAverageTheirTimingsPerWindow) {
  EXPECT_EQ(diagnostics.keyframeProcessed(loopResult(false), false, 1.0, 3.0), 0u);
  bowg::LoopResult metric = loopResult(true);
  metric.translation_scale_known = true;
  EXPECT_EQ(diagnostics.keyframeProcessed(metric, false, 3.0, 5.0), 1u);
  EXPECT_EQ(diagnostics.keyframeProcessed(loopResult(true), true, 2.0, 4.0), 2u);
  advance(2);
  auto status = diagnose();
  EXPECT_EQ(value(status, "keyframes"), "3");
  EXPECT_EQ(value(status, "loops found"), "2");
  EXPECT_EQ(value(status, "loops with a metric translation"), "1");
  EXPECT_EQ(value(status, "metric translations outside the odometry (published without scale)"),
            "1");
  EXPECT_EQ(value(status, "keyframe rate (Hz)"), "1.5");
  EXPECT_EQ(value(status, "ms convert"), "2");
  EXPECT_EQ(value(status, "ms features"), "4");
  EXPECT_EQ(value(status, "ms query"), "2");
  EXPECT_EQ(value(status, "ms total"), "11");  // 5 + convert + features
  // The next window starts empty; the totals stay.
  advance(1);
  status = diagnose();
  EXPECT_EQ(value(status, "keyframe rate (Hz)"), "0");
  EXPECT_EQ(value(status, "ms total"), "0");
  EXPECT_EQ(value(status, "keyframes"), "3");
}

TEST_F(NodeletDiagnosticsTest, QueueDropsWarnUntilTheyStopForTheWindow) {
  diagnostics.frameReceived(1.0, GateDecision::kAccept);
  nodelet.dropped = 4;
  auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::WARN);
  EXPECT_EQ(status.message,
            "keyframes dropped in the last 30 s: the detector is slower than the keyframe rate");
  EXPECT_EQ(value(status, "dropped frames (queue full)"), "4");
  advance(20);
  diagnostics.frameReceived(2.0, GateDecision::kAccept);
  EXPECT_EQ(diagnose().level, DiagnosticStatus::WARN);
  advance(11);  // 31 s since the count last grew
  diagnostics.frameReceived(3.0, GateDecision::kAccept);
  EXPECT_EQ(diagnose().level, DiagnosticStatus::OK);
  nodelet.dropped = 5;
  EXPECT_EQ(diagnose().level, DiagnosticStatus::WARN);
}

TEST_F(NodeletDiagnosticsTest, ADistanceGateWithoutOdometryWarnsOnceFramesArrive) {
  settings.distance_gate = true;
  diagnostics.configure(settings);
  EXPECT_EQ(diagnose().level, DiagnosticStatus::OK) << "no frame yet";
  diagnostics.frameReceived(1.0, GateDecision::kAccept);
  auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::WARN);
  EXPECT_EQ(status.message,
            "~min_keyframe_distance is set but no odometry arrived on /cam/odom, "
            "/cam/odometer or /cam/odometer_stamped: only the time gate applies");
  nodelet.has_odometry = true;
  status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::OK);
  EXPECT_EQ(value(status, "odometry input"), "odometer only");
  nodelet.has_positions = true;
  EXPECT_EQ(value(diagnose(), "odometry input"), "positions and odometer");
}

TEST_F(NodeletDiagnosticsTest, EveryReasonAtTheWorstLevelIsInTheMessage) {
  diagnostics.frameReceived(100.0, GateDecision::kAccept);
  diagnostics.frameReceived(100.0, GateDecision::kRepeatedStamp);
  nodelet.dropped = 1;
  const auto status = diagnose();
  EXPECT_EQ(status.level, DiagnosticStatus::WARN);
  EXPECT_EQ(status.message,
            "1 frames skipped for their stamps (latest: frame at 100.000000 s: same stamp as the "
            "previous frame); a replay that starts over needs ~reset or ~reset_on_time_jump; "
            "keyframes dropped in the last 30 s: the detector is slower than the keyframe rate");
}

}  // namespace
}  // namespace bowg_ros
