// From the loop detector's camera frames to the pose graph's body frames.
// A LoopClosure's relative pose is T_Q_M in REP-103 optical frames (x right,
// y down, z forward); a loop edge wants the query body in the match body's
// frame (REP-103 body: x forward, y left, z up). ROS-free.
#pragma once

#include <Eigen/Geometry>

namespace bowg {
namespace pose_graph {

/// The optical axes (right, down, forward) as columns in the body frame of
/// a camera looking along the body's x axis.
Eigen::Matrix3d bodyFromOptical();

/// The rotation of the query body in the match body frame, given the match
/// camera's rotation in the query's optical frame (camera at the body's
/// origin and looking along its x axis).
Eigen::Quaterniond queryInMatchBody(const Eigen::Quaterniond& query_R_match_optical);

}  // namespace pose_graph
}  // namespace bowg
