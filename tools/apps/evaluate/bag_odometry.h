// The odometry of a bag as the nodelet takes it: odometer readings
// (std_msgs/Float64 on --odometer-topic in bag order, or
// bowg_ros/OdometerStamped by stamp) and odometry positions
// (nav_msgs/Odometry on --odom-topic, by header stamp). A frame gets what
// the keyframe gate holds once the readings up to its stamp went in: the
// nodelet's OdometryMerge, with no time limit, and its KeyframeGate's path
// and position.
#pragma once

#include <rosbag/message_instance.h>
#include <rosbag/view.h>

#include <cstddef>
#include <string>
#include <vector>

#include "bowg_evaluation/detector_run.h"
#include "bowg_ros/keyframe_gate.h"
#include "bowg_ros/odometry_merge.h"

namespace bowg {
namespace evaluate_app {

class BagOdometry {
 public:
  /// Topics "" are not read. `frames` receives each frame's odometer and
  /// position as frameAdded() or a later reading settles it.
  BagOdometry(const std::string& bag, const std::string& odometer_topic,
              const std::string& odom_topic, std::vector<eval::FrameInput>* frames);

  /// From the bag's connections: a stamped odometer makes frames wait from
  /// the first one on (as the nodelet's do while that topic has a
  /// publisher).
  void expectStamped(rosbag::View& view);
  /// True for the topics read here.
  bool reads(const std::string& topic) const;
  /// One message of a topic read here; throws bowg::FormatError naming the
  /// bag for a type the nodelet does not take there.
  void reading(const rosbag::MessageInstance& m);
  /// frames->back() was just added, stamped `stamp`.
  void frameAdded(double stamp);
  /// Frames wait for stamped readings at or after their stamp.
  bool waiting() const { return merge_.waiting() > 0; }
  /// The frames no reading reached: the odometry of every reading. Warns on
  /// stderr, with their count, of positions whose orientation gave no
  /// heading (as the nodelet warns of them).
  void finish();

 private:
  void odometerReading(const rosbag::MessageInstance& m);
  void positionReading(const rosbag::MessageInstance& m);
  void settle(std::size_t frame);
  void release(bool all);
  void add(double stamp, const bowg_ros::OdometryReading& r);

  std::string bag_, odometer_topic_, odom_topic_;
  std::vector<eval::FrameInput>* frames_;
  bowg_ros::OdometryMerge<std::size_t> merge_;
  bool stamped_odometer_ = false;
  /// Positions read, those without a heading, and the first one's orientation.
  std::size_t positions_ = 0, without_heading_ = 0;
  std::string first_orientation_;
  /// The nodelet's sum and last position of the readings; frames are not
  /// gated here.
  bowg_ros::KeyframeGate gate_;
};

}  // namespace evaluate_app
}  // namespace bowg
