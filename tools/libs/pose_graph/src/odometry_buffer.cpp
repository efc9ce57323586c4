#include "bowg_pose_graph/odometry_buffer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bowg {
namespace pose_graph {

OdometryBuffer::OdometryBuffer(double horizon) : horizon_(horizon) {
  if (!(horizon > 0) || !std::isfinite(horizon)) {
    throw std::invalid_argument("OdometryBuffer: horizon must be a finite value > 0 s");
  }
}

void OdometryBuffer::add(double stamp, const Eigen::Isometry3d& pose) {
  if (!stamps_.empty() && !(stamp > stamps_.back())) {
    stamps_.clear();
    positions_.clear();
    rotations_.clear();
  }
  stamps_.push_back(stamp);
  positions_.push_back(pose.translation());
  rotations_.push_back(Eigen::Quaterniond(pose.rotation()).normalized());
  while (stamps_.size() > 2 && stamps_.front() < stamp - horizon_) {
    stamps_.pop_front();
    positions_.pop_front();
    rotations_.pop_front();
  }
}

bool OdometryBuffer::at(double stamp, Eigen::Isometry3d* pose) const {
  if (stamps_.empty() || stamp < stamps_.front() || stamp > stamps_.back()) return false;
  const std::size_t hi = std::lower_bound(stamps_.begin(), stamps_.end(), stamp) - stamps_.begin();
  Eigen::Vector3d p = positions_[hi];
  Eigen::Quaterniond q = rotations_[hi];
  if (stamps_[hi] != stamp) {
    const std::size_t lo = hi - 1;  // stamp > stamps_.front(), so hi >= 1
    const double f = (stamp - stamps_[lo]) / (stamps_[hi] - stamps_[lo]);
    p = (1 - f) * positions_[lo] + f * positions_[hi];
    q = rotations_[lo].slerp(f, rotations_[hi]);
  }
  *pose = Eigen::Isometry3d::Identity();
  pose->linear() = q.toRotationMatrix();
  pose->translation() = p;
  return true;
}

}  // namespace pose_graph
}  // namespace bowg
