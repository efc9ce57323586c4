#include "bowg_pose_graph/trajectory_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bowg {
namespace pose_graph {

TrajectoryError positionError(const std::vector<Eigen::Vector3d>& estimate,
                              const std::vector<Eigen::Vector3d>& truth) {
  if (estimate.size() != truth.size() || truth.empty()) {
    throw std::invalid_argument("positionError: " + std::to_string(estimate.size()) +
                                " estimated and " + std::to_string(truth.size()) +
                                " true positions (equal and > 0 needed)");
  }
  TrajectoryError e;
  e.frames = truth.size();
  double sum = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double d = (estimate[i] - truth[i]).norm();
    sum += d * d;
    e.max = std::max(e.max, d);
  }
  e.rmse = std::sqrt(sum / truth.size());
  e.last = (estimate.back() - truth.back()).norm();
  return e;
}

std::vector<Eigen::Vector3d> anchoredTruth(const PoseVector& truth, std::size_t anchor,
                                           const Eigen::Isometry3d& estimate_anchor) {
  if (anchor >= truth.size()) {
    throw std::invalid_argument("anchoredTruth: anchor " + std::to_string(anchor) + " of " +
                                std::to_string(truth.size()) + " true poses");
  }
  const Eigen::Isometry3d estimate_T_truth = estimate_anchor * truth[anchor].inverse();
  std::vector<Eigen::Vector3d> out;
  out.reserve(truth.size());
  for (const Eigen::Isometry3d& t : truth) out.push_back((estimate_T_truth * t).translation());
  return out;
}

}  // namespace pose_graph
}  // namespace bowg
