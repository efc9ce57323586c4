#include "bowg_pose_graph/mission_alignment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bowg {
namespace pose_graph {
namespace {

double median(std::vector<double> v) {
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  if (v.size() % 2 == 1) return v[mid];
  const double upper = v[mid];
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + mid));
}

// The heading of a body (its x axis) as a yaw about z.
double headingYaw(const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d x = pose.linear().col(0);
  return std::atan2(x.y(), x.x());
}

double wrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

Eigen::Isometry3d alignMission(const MissionLoopPairs& loops) {
  if (loops.empty()) throw std::invalid_argument("alignMission: no loop to place the mission by");
  // Yaw: wrapped about the first loop's, so that the median does not split
  // at +-180 deg.
  const double reference =
      headingYaw(loops[0].match_in_world) - headingYaw(loops[0].query_in_mission);
  std::vector<double> yaws;
  for (const MissionLoopPair& l : loops) {
    const double yaw = headingYaw(l.match_in_world) - headingYaw(l.query_in_mission);
    yaws.push_back(wrapAngle(yaw - reference));
  }
  const double yaw = wrapAngle(reference + median(yaws));
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  std::vector<double> t[3];
  for (const MissionLoopPair& l : loops) {
    const Eigen::Vector3d d = l.match_in_world.translation() - R * l.query_in_mission.translation();
    for (int i = 0; i < 3; ++i) t[i].push_back(d[i]);
  }
  Eigen::Isometry3d world_T_mission = Eigen::Isometry3d::Identity();
  world_T_mission.linear() = R;
  world_T_mission.translation() = Eigen::Vector3d(median(t[0]), median(t[1]), median(t[2]));
  return world_T_mission;
}

}  // namespace pose_graph
}  // namespace bowg
