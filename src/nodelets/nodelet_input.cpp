// LoopDetectorNodelet: the input callbacks. They only check, gate and enqueue
// (never block: the bounded queue drops the oldest frame); the worker converts.
// With stamped odometry (odom, odometer_stamped) a frame first waits,
// briefly, for the readings at its stamp (odometry_merge.h).
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
  if (!waitsForOdometry()) return admit(std::move(frame), false);
  odometry_merge_.addFrame(frame.header.stamp.toSec(), steadySeconds(), std::move(frame));
  releaseMerged();
}

bool LoopDetectorNodelet::waitsForOdometry() const {
  return odometry_merge_.hasReadings() || odometry_merge_.waiting() > 0 ||
         odometer_stamped_sub_.getNumPublishers() > 0;
}

void LoopDetectorNodelet::releaseMerged() {
  odometry_merge_.release(
      steadySeconds(), odometry_wait_, [this](const OdometryReading& r) { applyReading(r); },
      [this](Frame&& frame, bool late) { admit(std::move(frame), late); });
}

void LoopDetectorNodelet::admit(Frame frame, bool odometry_late) {
  const double stamp = frame.header.stamp.toSec();
  const GateDecision d = gate_.check(stamp);
  frame.odometer = gate_.odometer();
  frame.position = gate_.position();
  frame.heading = gate_.heading();
  frame.epoch = gate_.epoch();
  diagnostics_.frameReceived(stamp, d);
  if (odometry_late) {
    diagnostics_.odometryLate();
    NODELET_WARN_THROTTLE(5.0,
                          "frame at %.6f went on without the odometry at its stamp on %s or %s "
                          "(waited ~odometry_wait %.3f s): the latest readings before it are used",
                          stamp, publicName("odom").c_str(), publicName("odometer_stamped").c_str(),
                          odometry_wait_);
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
  if (odometry_merge_.hasReadings(OdometryReading::kOdometer)) {
    NODELET_INFO_ONCE("%s is ignored: stamped readings of the same odometer arrive on %s",
                      publicName("odometer").c_str(), publicName("odometer_stamped").c_str());
    return;
  }
  applyReading(OdometryReading::odometer(msg->data));
}

void LoopDetectorNodelet::odometerStampedCallback(const OdometerStamped::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(gate_mutex_);
  addStampedReading(msg->header.stamp.toSec(), OdometryReading::odometer(msg->metres),
                    "odometer_stamped");
}

void LoopDetectorNodelet::addStampedReading(double stamp, const OdometryReading& r,
                                            const char* topic) {
  if (!odometry_merge_.addReading(stamp, r)) {
    // Far back with ~reset_on_time_jump: a replay that started over.
    if (!isTimeJump(stamp, odometry_merge_.lastStamp(r.source), gate_options_.time_jump_reset)) {
      NODELET_WARN_THROTTLE(5.0, "reading at %.6f on %s is older than the previous: ignored", stamp,
                            publicName(topic).c_str());
      return;
    }
    odometry_merge_.restartReadings(r.source);
    odometry_merge_.addReading(stamp, r);
  }
  releaseMerged();
}

// Only odometer readings are ignored by the gate (a position is always taken).
void LoopDetectorNodelet::applyReading(const OdometryReading& r) {
  if (gate_.addReading(r)) return;
  if (std::isfinite(r.metres)) {
    NODELET_INFO_ONCE(
        "odometer readings (%s, %s) are ignored: odometry positions arrive on %s and measure "
        "the same path",
        publicName("odometer").c_str(), publicName("odometer_stamped").c_str(),
        publicName("odom").c_str());
  } else {
    NODELET_WARN_THROTTLE(5.0, "odometer reading %f is not finite: ignored", r.metres);
  }
}

void LoopDetectorNodelet::odometryCallback(const nav_msgs::OdometryConstPtr& msg) {
  const OdometryReading r = toReading(*msg);
  if (!r.heading.known()) {
    const geometry_msgs::Quaternion& q = msg->pose.pose.orientation;
    NODELET_WARN_ONCE(
        "%s orientation (%g, %g, %g, %g) is not a unit quaternion: its positions carry no "
        "heading, and the heading gate (heading_gate_deg) does not apply to their keyframes",
        publicName("odom").c_str(), q.x, q.y, q.z, q.w);
  }
  std::lock_guard<std::mutex> lock(gate_mutex_);
  if (!msg->header.stamp.isZero()) return addStampedReading(msg->header.stamp.toSec(), r, "odom");
  // Stamp 0 is ROS's "time unknown": such a position is taken on arrival.
  NODELET_INFO_ONCE("%s carries no stamps (0): each position is taken when it arrives",
                    publicName("odom").c_str());
  applyReading(r);
}

}  // namespace bowg_ros
