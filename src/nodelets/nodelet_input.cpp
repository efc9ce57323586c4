// LoopDetectorNodelet: the input callbacks. They only check, gate and enqueue
// (never block: the bounded queue drops the oldest frame); the worker converts.
// With a stamped odometer a frame first waits, briefly, for the reading at
// its stamp (odometer_merge.h).
#include <cmath>

#include "loop_detector_nodelet.h"

namespace bowg_ros {

namespace {

double steadySeconds() {
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

}  // namespace

void LoopDetectorNodelet::offer(Frame frame) {
  std::lock_guard<std::mutex> lock(gate_mutex_);
  if (!waitsForOdometer()) return admit(std::move(frame), false);
  odometer_merge_.addFrame(frame.header.stamp.toSec(), steadySeconds(), std::move(frame));
  releaseMerged();
}

bool LoopDetectorNodelet::waitsForOdometer() const {
  return odometer_merge_.hasReadings() || odometer_merge_.waiting() > 0 ||
         odometer_stamped_sub_.getNumPublishers() > 0;
}

void LoopDetectorNodelet::releaseMerged() {
  odometer_merge_.release(
      steadySeconds(), odometer_wait_, [this](double metres) { applyOdometerReading(metres); },
      [this](Frame&& frame, bool late) { admit(std::move(frame), late); });
}

void LoopDetectorNodelet::admit(Frame frame, bool odometer_late) {
  const double stamp = frame.header.stamp.toSec();
  const GateDecision d = gate_.check(stamp);
  frame.odometer = gate_.odometer();
  frame.position = gate_.position();
  frame.epoch = gate_.epoch();
  diagnostics_.frameReceived(stamp, d);
  if (odometer_late) {
    diagnostics_.odometerLate();
    NODELET_WARN_THROTTLE(5.0,
                          "frame at %.6f went on without the reading at its stamp on %s "
                          "(waited ~odometer_wait %.3f s): the latest reading before it is used",
                          stamp, publicName("odometer_stamped").c_str(), odometer_wait_);
  }
  if (isStampRejection(d)) {
    NODELET_WARN_THROTTLE(2.0,
                          "frame at %.6f skipped: %s (a replay that starts over: call ~reset, "
                          "or set ~reset_on_time_jump)",
                          stamp, toString(d));
    return;
  }
  if (d == GateDecision::kTimeJump) {
    NODELET_WARN(
        "time jumped back by more than ~reset_on_time_jump (frame at %.6f s): a new run, "
        "the database starts empty",
        stamp);
  }
  // Queued under the gate's lock: frames enter in the order the gate saw them.
  if (isKeyframe(d)) queue_->push(std::move(frame));
}

// Images are checked here, where the drop is counted, from the message
// header alone (layout and size, or the compressed data's own header); the
// worker converts or decodes only what passed.
void LoopDetectorNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg) {
  const bowg::ImageCheck check = checkImage(*msg, size_limit_);
  if (!check.ok()) return dropBadImage(check, msg->header.stamp);
  Frame frame;
  frame.header = msg->header;
  frame.image = msg;
  offer(std::move(frame));
}

void LoopDetectorNodelet::compressedCallback(const sensor_msgs::CompressedImageConstPtr& msg) {
  const bowg::ImageCheck check = checkCompressed(*msg, size_limit_);
  if (!check.ok()) return dropBadImage(check, msg->header.stamp);
  Frame frame;
  frame.header = msg->header;
  frame.compressed = msg;
  offer(std::move(frame));
}

void LoopDetectorNodelet::dropBadImage(const bowg::ImageCheck& check, const ros::Time& stamp) {
  // Counted in the diagnostics whatever the throttled log shows.
  if (diagnostics_.badImage(check.problem))
    NODELET_ERROR("image at %.6f dropped: %s", stamp.toSec(), check.message().c_str());
}

void LoopDetectorNodelet::featuresCallback(const KeyframeFeatures::ConstPtr& msg) {
  Frame frame;
  frame.header = msg->header;
  frame.features = msg;
  offer(std::move(frame));
}

void LoopDetectorNodelet::cameraInfoCallback(const sensor_msgs::CameraInfoConstPtr& msg) {
  diagnostics_.cameraInfoReceived();
  const bowg::CameraIntrinsics k = toIntrinsics(*msg);
  std::lock_guard<std::mutex> lock(gate_mutex_);
  intrinsics_ = k;
}

void LoopDetectorNodelet::odometerCallback(const std_msgs::Float64ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(gate_mutex_);
  if (odometer_merge_.hasReadings()) {
    NODELET_INFO_ONCE("%s is ignored: stamped readings of the same odometer arrive on %s",
                      publicName("odometer").c_str(), publicName("odometer_stamped").c_str());
    return;
  }
  applyOdometerReading(msg->data);
}

void LoopDetectorNodelet::odometerStampedCallback(const OdometerStamped::ConstPtr& msg) {
  const double stamp = msg->header.stamp.toSec();
  std::lock_guard<std::mutex> lock(gate_mutex_);
  if (!odometer_merge_.addReading(stamp, msg->metres)) {
    // Far back with ~reset_on_time_jump: a replay that started over.
    if (!isTimeJump(stamp, odometer_merge_.lastStamp(), gate_options_.time_jump_reset)) {
      NODELET_WARN_THROTTLE(5.0,
                            "odometer reading at %.6f on %s is older than the previous: ignored",
                            stamp, publicName("odometer_stamped").c_str());
      return;
    }
    odometer_merge_.restartReadings();
    odometer_merge_.addReading(stamp, msg->metres);
  }
  releaseMerged();
}

void LoopDetectorNodelet::applyOdometerReading(double metres) {
  if (gate_.addOdometerReading(metres)) return;
  if (std::isfinite(metres)) {
    NODELET_INFO_ONCE(
        "odometer readings (%s, %s) are ignored: odometry positions arrive on %s and measure "
        "the same path",
        publicName("odometer").c_str(), publicName("odometer_stamped").c_str(),
        publicName("odom").c_str());
  } else {
    NODELET_WARN_THROTTLE(5.0, "odometer reading %f is not finite: ignored", metres);
  }
}

void LoopDetectorNodelet::odometryCallback(const nav_msgs::OdometryConstPtr& msg) {
  const geometry_msgs::Point& p = msg->pose.pose.position;
  std::lock_guard<std::mutex> lock(gate_mutex_);
  gate_.addPosition(p.x, p.y, p.z);
}

}  // namespace bowg_ros
