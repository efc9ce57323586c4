// Odometry poses by stamp, for the live pose-graph node: a keyframe's pose is
// the odometry interpolated at its image's stamp (odometry and camera run at
// their own rates). ROS-free.
#pragma once

#include <Eigen/Geometry>
#include <Eigen/StdVector>
#include <deque>

namespace bowg {
namespace pose_graph {

class OdometryBuffer {
 public:
  /// Keeps the poses of the last `horizon` seconds (> 0).
  explicit OdometryBuffer(double horizon = 60.0);

  /// A pose at `stamp` (s). A stamp not after the newest one resets the
  /// buffer first (time jumped back: a replay started over).
  void add(double stamp, const Eigen::Isometry3d& pose);

  /// The pose at `stamp`: linear in position, spherical in rotation between
  /// the two poses around it. False when `stamp` lies outside the buffer.
  bool at(double stamp, Eigen::Isometry3d* pose) const;

  bool empty() const { return stamps_.empty(); }
  double newest() const { return stamps_.back(); }
  double oldest() const { return stamps_.front(); }

 private:
  double horizon_;
  std::deque<double> stamps_;
  std::deque<Eigen::Vector3d> positions_;
  std::deque<Eigen::Quaterniond, Eigen::aligned_allocator<Eigen::Quaterniond>> rotations_;
};

}  // namespace pose_graph
}  // namespace bowg
