#include "bowg_pose_graph/camera_frames.h"

namespace bowg {
namespace pose_graph {

Eigen::Matrix3d bodyFromOptical() {
  Eigen::Matrix3d m;
  // optical x (right) = body -y; optical y (down) = body -z; optical z = body x.
  m << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return m;
}

Eigen::Quaterniond queryInMatchBody(const Eigen::Quaterniond& query_R_match_optical) {
  const Eigen::Matrix3d c = bodyFromOptical();
  // Inverse (match_R_query), then conjugated into body axes.
  return Eigen::Quaterniond(c * query_R_match_optical.normalized().toRotationMatrix().transpose() *
                            c.transpose());
}

}  // namespace pose_graph
}  // namespace bowg
