#include "bowg_pose_graph/loop_translation_error.h"

#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>
#include <string>

namespace bowg {
namespace pose_graph {
namespace {

// The q-quantile by the nearest rank (sorted copy).
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t i = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

const double kChiSquare3Dof95 = 7.815;

}  // namespace

LoopTranslationError loopTranslationError(const std::vector<LoopEdge>& edges,
                                          const std::vector<Eigen::Isometry3d>& truth) {
  if (edges.size() != truth.size()) {
    throw std::invalid_argument("loopTranslationError: " + std::to_string(edges.size()) +
                                " edges and " + std::to_string(truth.size()) + " true poses");
  }
  LoopTranslationError out;
  out.loops = edges.size();
  std::vector<double> error, same_place;
  std::size_t inside = 0;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Eigen::Vector3d e = edges[i].position - truth[i].translation();
    error.push_back(e.norm());
    same_place.push_back(truth[i].translation().norm());
    if (e.dot(edges[i].position_covariance.inverse() * e) <= kChiSquare3Dof95) ++inside;
  }
  out.median = quantile(error, 0.5);
  out.p90 = quantile(error, 0.9);
  out.same_place_median = quantile(same_place, 0.5);
  out.same_place_p90 = quantile(same_place, 0.9);
  out.inside_95 =
      edges.empty() ? 0 : static_cast<double>(inside) / static_cast<double>(edges.size());
  return out;
}

}  // namespace pose_graph
}  // namespace bowg
