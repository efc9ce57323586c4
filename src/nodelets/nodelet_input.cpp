// LoopDetectorNodelet: the input callbacks. They only check, gate and enqueue
// (never block: the bounded queue drops the oldest frame); the worker converts.
#include <cmath>

#include "loop_detector_nodelet.h"

namespace bowg_ros {

bool LoopDetectorNodelet::offer(Frame frame) {
  const double stamp = frame.header.stamp.toSec();
  GateDecision d;
  {
    std::lock_guard<std::mutex> lock(gate_mutex_);
    d = gate_.check(stamp);
    frame.odometer = gate_.odometer();
    frame.position = gate_.position();
    frame.epoch = gate_.epoch();
  }
  diagnostics_.frameReceived(stamp, d);
  if (isStampRejection(d)) {
    NODELET_WARN_THROTTLE(2.0,
                          "frame at %.6f skipped: %s (a replay that starts over: call ~reset, "
                          "or set ~reset_on_time_jump)",
                          stamp, toString(d));
    return false;
  }
  if (d == GateDecision::kTimeJump) {
    NODELET_WARN(
        "time jumped back by more than ~reset_on_time_jump (frame at %.6f s): a new run, "
        "the database starts empty",
        stamp);
  }
  if (!isKeyframe(d)) return false;
  queue_->push(std::move(frame));
  return true;
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
  bool used;
  {
    std::lock_guard<std::mutex> lock(gate_mutex_);
    used = gate_.addOdometerReading(msg->data);
  }
  if (!used && std::isfinite(msg->data)) {
    NODELET_INFO_ONCE("%s is ignored: odometry positions arrive on %s and measure the same path",
                      publicName("odometer").c_str(), publicName("odom").c_str());
  } else if (!used) {
    NODELET_WARN_THROTTLE(5.0, "odometer reading %f on %s is not finite: ignored", msg->data,
                          publicName("odometer").c_str());
  }
}

void LoopDetectorNodelet::odometryCallback(const nav_msgs::OdometryConstPtr& msg) {
  const geometry_msgs::Point& p = msg->pose.pose.position;
  std::lock_guard<std::mutex> lock(gate_mutex_);
  gate_.addPosition(p.x, p.y, p.z);
}

}  // namespace bowg_ros
