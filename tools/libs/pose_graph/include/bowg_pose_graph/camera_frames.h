// From the loop detector's camera frames to the pose graph's body frames.
// A LoopClosure's relative pose is T_Q_M in REP-103 optical frames (x right,
// y down, z forward); a loop edge wants the query body in the match body's
// frame (REP-103 body: x forward, y left, z up). ROS-free.
#pragma once

#include <Eigen/Geometry>

#include "bowg_pose_graph/pose_graph.h"

namespace bowg {
namespace pose_graph {

/// The optical axes (right, down, forward) as columns in the body frame of
/// a camera looking along the body's x axis.
Eigen::Matrix3d bodyFromOptical();

/// The rotation of the query body in the match body frame, given the match
/// camera's rotation in the query's optical frame (camera at the body's
/// origin and looking along its x axis).
Eigen::Quaterniond queryInMatchBody(const Eigen::Quaterniond& query_R_match_optical);

/// The loop edge (without its node indices) for a camera mounted at
/// `body_T_optical` (its optical frame in the body frame, e.g. from TF): the
/// two cameras stood at the same place, so with the rotation R of the query
/// body in the match body, the query body lies at t - R t in the match body
/// (t: the camera's offset). With `use_rotation` false the rotation is not
/// constrained; the position is then 0, give or take the offset's length
/// (extra_position_sigma = |t|).
LoopEdge loopEdgeForCamera(const Eigen::Quaterniond& query_R_match_optical,
                           const Eigen::Isometry3d& body_T_optical, bool use_rotation);

/// The loop edge of a metric loop (LoopClosure.translation_scale_known):
/// the match camera's pose in the query's optical frame, query_T_match
/// (rotation and metres), and the covariance of its translation (m^2, query
/// optical frame), for a camera mounted at `body_T_optical`. The edge holds
/// the query body's pose in the match body, B query_T_match^-1 B^-1 (B =
/// body_T_optical), with the translation's covariance carried into the match
/// body frame to first order: the position is -B_R R^T t + const, so its
/// covariance is (B_R R^T) C (B_R R^T)^T.
LoopEdge metricLoopEdge(const Eigen::Isometry3d& query_T_match_optical,
                        const Eigen::Matrix3d& translation_covariance,
                        const Eigen::Isometry3d& body_T_optical);

/// body_T_optical of a camera at the body's origin looking along body x.
Eigen::Isometry3d cameraAtBodyOrigin();

}  // namespace pose_graph
}  // namespace bowg
