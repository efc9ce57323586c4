// How far an estimated trajectory lies from the truth: position errors per
// frame, in the truth's world frame (the offline graph is anchored at the
// true first pose, so no alignment is applied). A live robot's ground truth
// comes in a world frame of its own: anchoredTruth() carries it onto the
// estimate's frame first, by one rigid motion, not a best fit (a fit would
// hide part of the drift being measured).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/StdVector>
#include <cstddef>
#include <vector>

namespace bowg {
namespace pose_graph {

/// Poses of a trajectory (fixed-size Eigen members need the allocator).
using PoseVector = std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>;

struct TrajectoryError {
  std::size_t frames = 0;
  double rmse = 0;  ///< sqrt(mean |p_est - p_true|^2), m
  double max = 0;   ///< m
  double last = 0;  ///< error of the last frame, m
};

/// Over the frames both hold (index-aligned; throws std::invalid_argument
/// when the sizes differ or are 0).
TrajectoryError positionError(const std::vector<Eigen::Vector3d>& estimate,
                              const std::vector<Eigen::Vector3d>& truth);

/// The positions of `truth` moved by the rigid motion that takes
/// truth[anchor] onto `estimate_anchor` (the estimate's pose of the same
/// frame): every error is then measured from where both trajectories agree.
/// Throws std::invalid_argument when `anchor` is not an index of `truth`.
std::vector<Eigen::Vector3d> anchoredTruth(const PoseVector& truth, std::size_t anchor,
                                           const Eigen::Isometry3d& estimate_anchor);

}  // namespace pose_graph
}  // namespace bowg
