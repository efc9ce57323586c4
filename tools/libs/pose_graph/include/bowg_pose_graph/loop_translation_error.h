// How well metric loop edges (camera_frames.h, metricLoopEdge) place the
// query: their positions against the true ones, beside what the "same place"
// edge assumes (position 0), and how often the truth lies inside the edge's
// own 95 % covariance ellipsoid (is the covariance honest?).
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "bowg_pose_graph/pose_graph.h"

namespace bowg {
namespace pose_graph {

struct LoopTranslationError {
  std::size_t loops = 0;
  /// |measured - true| position of the query body in the match body (m).
  double median = 0, p90 = 0;
  /// |true position|: the error of the "same place" edge (m).
  double same_place_median = 0, same_place_p90 = 0;
  /// Share of loops whose error e has e^T C^-1 e <= 7.815 (chi-square, 3
  /// degrees of freedom, 95 %): 0.95 for an honest covariance.
  double inside_95 = 0;
};

/// `edges` (with has_position_covariance) against `truth`: the true pose of
/// each query body in its match body, index-aligned. Throws
/// std::invalid_argument when the sizes differ.
LoopTranslationError loopTranslationError(const std::vector<LoopEdge>& edges,
                                          const std::vector<Eigen::Isometry3d>& truth);

}  // namespace pose_graph
}  // namespace bowg
