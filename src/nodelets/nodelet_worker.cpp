// LoopDetectorNodelet: the worker thread. Grey image, features, one
// LoopDetector::process() per keyframe under the detector lock.
#include "loop_detector_nodelet.h"

namespace bowg_ros {

void LoopDetectorNodelet::workerLoop() {
  Frame frame;
  while (queue_->pop(&frame)) {
    try {
      processFrame(frame);
    } catch (const std::exception& e) {
      diagnostics_.keyframeError();
      NODELET_ERROR_THROTTLE(2.0, "keyframe at %.6f skipped: %s", frame.header.stamp.toSec(),
                             e.what());
    }
    frame = Frame();  // release the image now, not at the next pop
  }
}

// One line when the keyframes' odometry input changes (at the first
// keyframe, and when odometry starts or stops arriving): which acceptance is
// in force. Images only is a WARN with what to set.
void LoopDetectorNodelet::reportOdometryInput(bowg::OdometryInput input) {
  if (logged_input_ == static_cast<int>(input)) return;
  logged_input_ = static_cast<int>(input);
  if (input == bowg::OdometryInput::kNone) {
    NODELET_WARN("odometry input: %s (nothing on %s, %s or %s; ~min_keyframe_interval is %.3f s)",
                 bowg::describeAcceptance(input), publicName("odom").c_str(),
                 publicName("odometer").c_str(), publicName("odometer_stamped").c_str(),
                 gate_options_.min_interval);
  } else {
    NODELET_INFO("odometry input: %s", bowg::describeAcceptance(input));
  }
}

bowg::CameraIntrinsics LoopDetectorNodelet::currentIntrinsics() {
  bowg::CameraIntrinsics intrinsics;
  {
    std::lock_guard<std::mutex> lock(gate_mutex_);
    intrinsics = intrinsics_;
  }
  if (!intrinsics.valid && !intrinsics_warned_) {
    intrinsics_warned_ = true;
    NODELET_WARN(
        "no valid camera_info yet: loop closures carry no relative pose "
        "(has_relative_pose = false) until one arrives");
  }
  return intrinsics;
}

void LoopDetectorNodelet::processFrame(const Frame& frame) {
  // 1. Grey image (shared for mono8) or upstream features.
  auto t0 = Clock::now();
  cv::Mat grey;
  try {
    if (frame.image) {
      grey = greyFromImage(*frame.image, size_limit_);
    } else if (frame.compressed) {
      // Its header passed the callback; the data past it may still fail.
      grey = greyFromCompressed(*frame.compressed, size_limit_);
    }
  } catch (const BadImage& e) {
    return dropBadImage(e.check(), frame.header.stamp);
  }
  const double convert_ms = msSince(t0);

  bowg::KeyframeInput input;
  input.stamp = frame.header.stamp.toSec();
  input.odometer = frame.odometer;
  input.position = frame.position;
  input.heading = frame.heading;
  input.intrinsics = currentIntrinsics();

  std::lock_guard<std::mutex> lock(detector_mutex_);
  if (frame.epoch != worker_epoch_) {
    // The first keyframe after time jumped back (KeyframeGate, kTimeJump):
    // the frames queued before it were processed into the old run.
    NODELET_WARN("new run after a time jump: forgetting %zu keyframes",
                 detector_->database().size());
    restartRun(RunStart::kAfterTimeJump);
    worker_epoch_ = frame.epoch;
  }
  t0 = Clock::now();
  if (frame.features) {
    input.features = fromMessage(*frame.features, size_limit_);
  } else {
    input.features = extractor_->extract(grey);
  }
  const double feature_ms = frame.features ? 0.0 : msSince(t0);
  const std::size_t num_features = input.features.size();

  const bowg::LoopResult result = detector_->process(input);
  reportOdometryInput(result.odometry_input);
  const std::size_t database_size = detector_->database().size();

  publishResult(frame, result, grey, num_features, database_size, convert_ms, feature_ms);
  reportKeyframe(result, convert_ms, feature_ms);
}

void LoopDetectorNodelet::reportKeyframe(const bowg::LoopResult& result, double convert_ms,
                                         double feature_ms) {
  const bool found = result.status == bowg::LoopStatus::kLoopDetected;
  const bool outside_odometry =
      found && result.metric_status == bowg::MetricTranslationStatus::kOutsideOdometry;
  if (outside_odometry) {
    NODELET_WARN_THROTTLE(2.0,
                          "loop %u -> %u: its metric translation is longer than the odometry "
                          "gates allow between the two keyframes; published without scale",
                          result.query_id, result.match_id);
  }
  const std::size_t loops =
      diagnostics_.keyframeProcessed(result, outside_odometry, convert_ms, feature_ms);
  // Each loop at DEBUG (a robot on a revisit closes several a second); at
  // INFO a line every 10 s at most while loops come.
  if (found) {
    NODELET_INFO_THROTTLE(10.0, "%zu loops so far; the latest: keyframe %u matches %u (%d inliers)",
                          loops, result.query_id, result.match_id, result.inliers);
  }
}

}  // namespace bowg_ros
