// The rosbag of bowg_generate_pipe_sequence (--bag): per frame the image in
// the chosen format (--bag-images), the camera info, the ground-truth pose
// and the drifting odometry. It is written to FILE.tmp and renamed to FILE once complete, so an
// interrupted run leaves no bag that looks finished.
#pragma once

#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>

#include <opencv2/core.hpp>
#include <string>

#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/pipe_sequence.h"

namespace bowg {
namespace generate_pipe_sequence_app {

class BagOutput {
 public:
  /// Opens `path`.tmp with `compression` (none, lz4 or bz2); `image_format`
  /// is mono8, bgr8 or jpeg.
  BagOutput(const std::string& path, const std::string& compression,
            const std::string& image_format, const pipe_sim::CameraModel& camera);

  /// Frame `f`'s image, camera info and true pose (orientation quaternion
  /// `q`, x y z w) on /ground_truth/pose and /ground_truth/odom, stamped
  /// f.stamp.
  void write(const pipe_sim::FrameState& f, const cv::Mat& image, const cv::Vec4d& q);

  /// Frame `f`'s odometry on /odom: `pose` (orientation `q`, x y z w) with
  /// `covariance` (x y z, rotation about x y z), stamped f.stamp; and on
  /// /odometer (std_msgs/Float64) the path length of the odometry's
  /// positions so far, what a robot without positions counts (a cable
  /// counter), and the same on /odometer_stamped (bowg_ros/OdometerStamped,
  /// its header stamped f.stamp); all three recorded kOdometerLead before
  /// the frame so that a player delivers them before the frame's image.
  void writeOdometry(const pipe_sim::FrameState& f, const pipe_sim::CameraPose& pose,
                     const cv::Vec4d& q, const cv::Matx<double, 6, 6>& covariance);

  /// The next odometry belongs to a new run (another mission's, in a frame
  /// of its own): /odometer keeps counting from where it is, without the
  /// jump between the runs' positions.
  void startOdometryRun() { has_position_ = false; }

  /// Closes the bag and renames it to its final path.
  void finish();

 private:
  rosbag::Bag bag_;
  std::string path_, tmp_path_, image_format_;
  sensor_msgs::CameraInfo info_;
  bool has_position_ = false;
  cv::Vec3d last_position_;
  double odometer_ = 0;
};

/// How long before its frame's image the odometry is recorded in the bag (s).
constexpr double kOdometerLead = 0.02;

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
