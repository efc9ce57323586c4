// The pose-graph example's picture (bowg_pose_graph's trajectories.png): the
// trajectories seen from above (x-y), truth, odometry and optimised, with the
// loops drawn over them.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

namespace bowg {
namespace pose_graph {

/// A BGR image `size` px square: truth black, odometry red, optimised blue;
/// each loop (query, match indices into the vectors) a thin grey line from
/// the query's optimised position to the match's, with a grey ring at the
/// query (a same-place loop's ends meet once corrected: the ring still shows
/// it); a legend and a scale bar.
cv::Mat plotTopView(const std::vector<Eigen::Vector3d>& truth,
                    const std::vector<Eigen::Vector3d>& odometry,
                    const std::vector<Eigen::Vector3d>& optimised,
                    const std::vector<std::pair<std::size_t, std::size_t>>& loops, int size = 900);

}  // namespace pose_graph
}  // namespace bowg
