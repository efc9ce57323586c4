// A bag's odometry as the nodelet takes it (see bag_odometry.h).
#include "bag_odometry.h"

#include <nav_msgs/Odometry.h>
#include <std_msgs/Float64.h>

#include <cstdio>
#include <limits>

#include "bowg/core/errors.h"
#include "bowg_ros/OdometerStamped.h"
#include "bowg_ros/ros_conversions.h"

namespace bowg {
namespace evaluate_app {

using bowg_ros::OdometryReading;
using bowg_ros::toReading;

BagOdometry::BagOdometry(const std::string& bag, const std::string& odometer_topic,
                         const std::string& odom_topic, std::vector<eval::FrameInput>* frames)
    : bag_(bag),
      odometer_topic_(odometer_topic),
      odom_topic_(odom_topic),
      frames_(frames),
      merge_(std::numeric_limits<std::size_t>::max()) {}

void BagOdometry::expectStamped(rosbag::View& view) {
  for (const rosbag::ConnectionInfo* c : view.getConnections()) {
    if (!odometer_topic_.empty() && c->topic == odometer_topic_ &&
        c->datatype == "bowg_ros/OdometerStamped") {
      stamped_odometer_ = true;
    }
  }
}

bool BagOdometry::reads(const std::string& topic) const {
  return !topic.empty() && (topic == odometer_topic_ || topic == odom_topic_);
}

void BagOdometry::reading(const rosbag::MessageInstance& m) {
  if (m.getTopic() == odom_topic_) return positionReading(m);
  odometerReading(m);
}

void BagOdometry::odometerReading(const rosbag::MessageInstance& m) {
  if (const std_msgs::Float64::ConstPtr r = m.instantiate<std_msgs::Float64>()) {
    if (!stamped_odometer_) gate_.addOdometerReading(r->data);  // stamped ones win, as live
    return;
  }
  const bowg_ros::OdometerStamped::ConstPtr r = m.instantiate<bowg_ros::OdometerStamped>();
  if (!r) {
    throw FormatError(bag_ + ": " + odometer_topic_ +
                      " is neither std_msgs/Float64 nor bowg_ros/OdometerStamped");
  }
  stamped_odometer_ = true;
  add(r->header.stamp.toSec(), OdometryReading::odometer(r->metres));
}

void BagOdometry::positionReading(const rosbag::MessageInstance& m) {
  const nav_msgs::Odometry::ConstPtr o = m.instantiate<nav_msgs::Odometry>();
  if (!o) throw FormatError(bag_ + ": " + odom_topic_ + " is not nav_msgs/Odometry");
  const OdometryReading r = toReading(*o);
  ++positions_;
  if (!r.heading.known() && without_heading_++ == 0) {
    const geometry_msgs::Quaternion& q = o->pose.pose.orientation;
    char text[128];
    std::snprintf(text, sizeof text, "(%g, %g, %g, %g)", q.x, q.y, q.z, q.w);
    first_orientation_ = text;
  }
  // Stamp 0 ("time unknown"): taken in bag order, as the nodelet takes it on arrival.
  if (o->header.stamp.isZero()) return (void)gate_.addReading(r);
  add(o->header.stamp.toSec(), r);
}

// A reading older than its source's previous is dropped, as the nodelet
// drops it (a bag is not replayed within itself: no time jump here).
void BagOdometry::add(double stamp, const OdometryReading& r) {
  if (merge_.addReading(stamp, r)) release(false);
}

void BagOdometry::frameAdded(double stamp) {
  const std::size_t i = frames_->size() - 1;
  if (!stamped_odometer_ && !merge_.hasReadings()) return settle(i);
  merge_.addFrame(stamp, 0.0, i);
  release(false);
}

void BagOdometry::settle(std::size_t frame) {
  (*frames_)[frame].odometer = gate_.odometer();
  (*frames_)[frame].position = gate_.position();
  (*frames_)[frame].heading = gate_.heading();
}

void BagOdometry::finish() {
  release(true);
  if (without_heading_ == 0) return;
  std::fprintf(stderr,
               "warning: %zu of %zu positions on %s have an orientation that is not a unit "
               "quaternion (the first: %s): their keyframes carry no heading, and the heading "
               "gate (heading_gate_deg) does not apply to them\n",
               without_heading_, positions_, odom_topic_.c_str(), first_orientation_.c_str());
}

// Every frame "arrives" at 0 and waits 1 s: no frame is late before the
// end, where all go on (now 1).
void BagOdometry::release(bool all) {
  merge_.release(
      all ? 1.0 : 0.0, 1.0, [this](const OdometryReading& r) { gate_.addReading(r); },
      [this](std::size_t&& i, bool) { settle(i); });
}

}  // namespace evaluate_app
}  // namespace bowg
