// LoopDetectorNodelet: the input callbacks. They only check, gate and enqueue
// (never block: the bounded queue drops the oldest frame); the worker converts.
#include "loop_detector_nodelet.h"

namespace bowg_ros {

bool LoopDetectorNodelet::offer(Frame frame) {
  GateDecision d;
  {
    std::lock_guard<std::mutex> lock(gate_mutex_);
    d = gate_.check(frame.header.stamp.toSec());
    frame.odometer = gate_.odometer();
  }
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.frames_received;
    if (d == GateDecision::kOutOfOrder || d == GateDecision::kRepeatedStamp) {
      ++stats_.skipped_out_of_order;
    }
  }
  if (d == GateDecision::kOutOfOrder || d == GateDecision::kRepeatedStamp) {
    NODELET_WARN_THROTTLE(2.0, "frame at %.6f skipped: %s", frame.header.stamp.toSec(),
                          toString(d));
    return false;
  }
  if (d != GateDecision::kAccept) return false;
  queue_->push(std::move(frame));
  return true;
}

void LoopDetectorNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg) {
  if (!isSupportedEncoding(msg->encoding)) {
    {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      ++stats_.bad_encoding;
    }
    NODELET_ERROR_THROTTLE(5.0, "unsupported image encoding '%s' (supported: %s): frame dropped",
                           msg->encoding.c_str(), supportedEncodings().c_str());
    return;
  }
  // The layout is checked here, where the drop is counted; the worker
  // converts the message (greyFromImage), sharing its buffer for mono8.
  const std::string problem =
      imageLayoutProblem(msg->width, msg->height, msg->step, msg->data.size(), msg->encoding);
  if (!problem.empty()) {
    // Counted in the diagnostics whatever the throttled log shows.
    {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      ++stats_.malformed;
    }
    NODELET_ERROR_THROTTLE(5.0, "malformed image at %.6f (encoding '%s'): %s: frame dropped",
                           msg->header.stamp.toSec(), msg->encoding.c_str(), problem.c_str());
    return;
  }
  if (!imageSizeAccepted(msg->width, msg->height, msg->header.stamp)) return;
  Frame frame;
  frame.header = msg->header;
  frame.image = msg;
  offer(std::move(frame));
}

bool LoopDetectorNodelet::imageSizeAccepted(std::uint32_t width, std::uint32_t height,
                                            const ros::Time& stamp) {
  const std::string problem = bowg::imageSizeProblem(width, height, size_limit_);
  if (problem.empty()) return true;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.too_large;
  }
  NODELET_ERROR_THROTTLE(5.0, "image at %.6f too large: %s: frame dropped", stamp.toSec(),
                         problem.c_str());
  return false;
}

void LoopDetectorNodelet::compressedCallback(const sensor_msgs::CompressedImageConstPtr& msg) {
  Frame frame;
  frame.header = msg->header;
  frame.compressed = msg;
  offer(std::move(frame));
}

void LoopDetectorNodelet::featuresCallback(const KeyframeFeatures::ConstPtr& msg) {
  Frame frame;
  frame.header = msg->header;
  frame.features = msg;
  offer(std::move(frame));
}

void LoopDetectorNodelet::cameraInfoCallback(const sensor_msgs::CameraInfoConstPtr& msg) {
  const bowg::CameraIntrinsics k = toIntrinsics(*msg);
  std::lock_guard<std::mutex> lock(intrinsics_mutex_);
  intrinsics_ = k;
}

void LoopDetectorNodelet::odometryCallback(const nav_msgs::OdometryConstPtr& msg) {
  const geometry_msgs::Point& p = msg->pose.pose.position;
  std::lock_guard<std::mutex> lock(gate_mutex_);
  gate_.addPosition(p.x, p.y, p.z);
}

}  // namespace bowg_ros
