#include "bowg_pose_graph/camera_frames.h"

namespace bowg {
namespace pose_graph {

Eigen::Matrix3d bodyFromOptical() {
  Eigen::Matrix3d m;
  // optical x (right) = body -y; optical y (down) = body -z; optical z = body x.
  m << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return m;
}

namespace {

Eigen::Quaterniond inBody(const Eigen::Quaterniond& query_R_match_optical,
                          const Eigen::Matrix3d& body_R_optical) {
  // Inverse (match_R_query), then conjugated into body axes.
  return Eigen::Quaterniond(body_R_optical *
                            query_R_match_optical.normalized().toRotationMatrix().transpose() *
                            body_R_optical.transpose());
}

}  // namespace

Eigen::Quaterniond queryInMatchBody(const Eigen::Quaterniond& query_R_match_optical) {
  return inBody(query_R_match_optical, bodyFromOptical());
}

Eigen::Isometry3d cameraAtBodyOrigin() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = bodyFromOptical();
  return t;
}

LoopEdge loopEdgeForCamera(const Eigen::Quaterniond& query_R_match_optical,
                           const Eigen::Isometry3d& body_T_optical, bool use_rotation) {
  LoopEdge edge;
  const Eigen::Vector3d offset = body_T_optical.translation();
  if (use_rotation) {
    edge.has_rotation = true;
    edge.rotation = inBody(query_R_match_optical, body_T_optical.rotation());
    edge.position = offset - edge.rotation * offset;
  } else {
    edge.extra_position_sigma = offset.norm();
  }
  return edge;
}

LoopEdge metricLoopEdge(const Eigen::Isometry3d& query_T_match_optical,
                        const Eigen::Matrix3d& translation_covariance,
                        const Eigen::Isometry3d& body_T_optical) {
  const Eigen::Isometry3d match_T_query_body =
      body_T_optical * query_T_match_optical.inverse() * body_T_optical.inverse();
  LoopEdge edge;
  edge.has_rotation = true;
  edge.rotation = Eigen::Quaterniond(match_T_query_body.rotation()).normalized();
  edge.position = match_T_query_body.translation();
  const Eigen::Matrix3d J =
      body_T_optical.rotation() * query_T_match_optical.rotation().transpose();
  edge.has_position_covariance = true;
  edge.position_covariance = J * translation_covariance * J.transpose();
  // Exactly symmetric: the graph checks it.
  edge.position_covariance =
      0.5 * (edge.position_covariance + edge.position_covariance.transpose()).eval();
  return edge;
}

}  // namespace pose_graph
}  // namespace bowg
