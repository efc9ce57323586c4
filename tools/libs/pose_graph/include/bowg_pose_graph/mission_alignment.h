// Where a later mission's odometry frame lies in the graph's world (the
// first mission's frame): a robot starting a new survey starts a new
// odometry frame, and nothing but its loops into the earlier surveys says
// how the two relate. The pose graph needs a start near the answer (its
// rotations are not convex), so the later mission's odometry is first
// carried into the world by the rigid motion its loops agree on, then the
// graph refines it with every loop.
//
// Odometry frames share gravity (REP-103: z up; a wheel or cable odometry
// drifts in yaw, not in tilt), so the motion is a yaw about z and a
// translation. A loop says the query stands where the match stood, facing
// the same way along the pipe (the roll about the pipe axis may differ:
// the heading is the body's x axis, roll-free).
#pragma once

#include <Eigen/Geometry>
#include <Eigen/StdVector>
#include <vector>

namespace bowg {
namespace pose_graph {

/// One loop from the mission being placed into an earlier, placed one.
struct MissionLoopPair {
  Eigen::Isometry3d query_in_mission;  ///< the query's pose in the mission's odometry frame
  Eigen::Isometry3d match_in_world;    ///< the match's pose in the world (its estimate)
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};
using MissionLoopPairs = std::vector<MissionLoopPair, Eigen::aligned_allocator<MissionLoopPair>>;

/// world_T_mission: the yaw about z and the translation on which the loops
/// agree, robustly: each loop gives the yaw that turns the query's heading
/// onto the match's and then the translation that puts the query on the
/// match; the median of each (the yaw's about the first loop's, wrapped)
/// keeps a few wrong loops from moving it. Throws std::invalid_argument
/// without a loop.
Eigen::Isometry3d alignMission(const MissionLoopPairs& loops);

}  // namespace pose_graph
}  // namespace bowg
