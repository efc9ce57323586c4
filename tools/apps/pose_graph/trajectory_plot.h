// The pose-graph example's picture: the trajectories seen from above (x-y),
// truth, odometry and optimised, with the loops as lines.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

namespace bowg {
namespace pose_graph_app {

/// A BGR image `size` px square: truth black, odometry red, optimised blue,
/// loops (query, match indices into the vectors) grey between the optimised
/// positions; a legend and a scale bar.
cv::Mat plotTopView(const std::vector<Eigen::Vector3d>& truth,
                    const std::vector<Eigen::Vector3d>& odometry,
                    const std::vector<Eigen::Vector3d>& optimised,
                    const std::vector<std::pair<std::size_t, std::size_t>>& loops, int size = 900);

}  // namespace pose_graph_app
}  // namespace bowg
