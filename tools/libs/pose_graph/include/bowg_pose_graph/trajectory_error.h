// How far an estimated trajectory lies from the truth: position errors per
// frame, in the truth's world frame (the graph is anchored at the true first
// pose, so no alignment is applied).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace bowg {
namespace pose_graph {

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

}  // namespace pose_graph
}  // namespace bowg
