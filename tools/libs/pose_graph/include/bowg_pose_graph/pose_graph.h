// A small 3-D pose graph, the back end of the pose-graph example: one node
// per keyframe (the pose of the robot body in the world), odometry edges
// between consecutive keyframes and loop edges from the loop detector,
// optimised with Ceres (robust loss on the loops, first pose held fixed).
//
// What a loop edge says: with a metric translation (the detector's, scaled
// by the odometry: LoopClosure.translation_scale_known) the query's pose in
// the match body frame as measured, with the measurement's covariance.
// Without it, in a pipe a loop means "the same place" within the detector's
// tolerance, so the query's position in the match body frame is
// 0 +- position_sigma (a few keyframes of spacing); the relative rotation is
// added when it is known (the essential matrix's, in the body frame) and
// left free otherwise (the robot may pass the place rolled differently).
// ROS-free.
#pragma once

#include <Eigen/Geometry>
#include <Eigen/StdVector>
#include <cstddef>
#include <string>
#include <vector>

namespace bowg {
namespace pose_graph {

struct PoseGraphOptions {
  /// Odometry edge: sigma of each step's position = fraction x step length
  /// + floor (m); of its rotation = drift x sqrt(step length) + floor.
  double odometry_position_fraction = 0.05;
  double odometry_position_floor = 0.002;
  double odometry_rotation_deg_per_sqrt_m = 2.0;
  double odometry_rotation_floor_deg = 0.05;
  /// Loop edge: sigma of the query's position in the match frame (m) and of
  /// the relative rotation (deg, when given).
  double loop_position_sigma = 0.15;
  double loop_rotation_sigma_deg = 3.0;
  /// Cauchy loss scale on the loop residuals, in sigmas: a loop that
  /// disagrees with the rest by much more than this is down-weighted; 0 =
  /// plain least squares.
  double loop_robust_sigmas = 3.0;
  int max_iterations = 200;
  void validate() const;  ///< throws std::invalid_argument naming the field
};

struct LoopEdge {
  std::size_t query = 0, match = 0;
  /// Expected position of the query body in the match body frame (m).
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  bool has_rotation = false;
  /// Rotation of the query body in the match body frame (when has_rotation).
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  /// Added (in quadrature) to loop_position_sigma: what the edge does not
  /// know of the position, such as a camera's offset from the body when the
  /// rotation is unknown (m, >= 0).
  double extra_position_sigma = 0;
  /// A measured position: its covariance (m^2, match body frame) replaces
  /// loop_position_sigma (extra_position_sigma still adds to its diagonal).
  bool has_position_covariance = false;
  Eigen::Matrix3d position_covariance = Eigen::Matrix3d::Identity();
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct SolveSummary {
  int iterations = 0;
  double initial_cost = 0, final_cost = 0;
  bool converged = false;
  std::string report;  ///< Ceres' one-line report
};

class PoseGraph {
 public:
  explicit PoseGraph(const PoseGraphOptions& options = PoseGraphOptions());

  /// A node with its initial estimate; returns its index (0, 1, ...). The
  /// first node is held fixed (it anchors the graph).
  std::size_t addPose(const Eigen::Isometry3d& initial);
  /// Measured motion from node `from` to node `to`: the pose of `to` in the
  /// body frame of `from`.
  void addOdometry(std::size_t from, std::size_t to, const Eigen::Isometry3d& from_T_to);
  /// Throws std::invalid_argument for nodes it does not join, a negative
  /// extra sigma or a position covariance that is not one.
  void addLoop(const LoopEdge& loop);

  SolveSummary optimize();

  std::size_t size() const { return positions_.size(); }
  Eigen::Isometry3d pose(std::size_t i) const;

 private:
  struct Odometry {
    std::size_t from, to;
    Eigen::Isometry3d from_T_to;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
  };
  // Fixed-size vectorisable Eigen types in std::vector need Eigen's
  // allocator before C++17.
  template <typename T>
  using AlignedVector = std::vector<T, Eigen::aligned_allocator<T>>;
  PoseGraphOptions options_;
  // Node parameters as Ceres sees them: position (x, y, z) and an Eigen
  // quaternion (x, y, z, w).
  std::vector<Eigen::Vector3d> positions_;
  AlignedVector<Eigen::Quaterniond> rotations_;
  AlignedVector<Odometry> odometry_;
  AlignedVector<LoopEdge> loops_;
};

}  // namespace pose_graph
}  // namespace bowg
