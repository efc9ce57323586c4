// The missions of the pose-graph example (`bowg_pose_graph --missions
// FILE`): each survey's odometry is a frame of its own, so no odometry edge
// joins two missions, and a later mission enters the graph where its loops
// into the earlier ones put it (mission_alignment.h); the report gives each
// later mission's error against the truth in its own frame, once placed by
// its loops and after the graph.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "bowg_evaluation/mission_file.h"
#include "bowg_pose_graph/trajectory_error.h"

namespace bowg {
namespace pose_graph_app {

struct MissionSpan {
  std::uint32_t id = 0;
  std::string name;
  std::size_t first = 0, end = 0;  ///< its nodes [first, end)
};

/// The missions' nodes; `frame_of_node` gives each node's frame. Throws
/// FormatError (naming `source`) when a mission starts at a frame no node
/// has.
std::vector<MissionSpan> missionSpans(const std::vector<eval::MissionStart>& starts,
                                      const std::vector<int>& frame_of_node,
                                      const std::string& source);

/// Whether nodes a and b belong to one mission.
bool sameMission(const std::vector<MissionSpan>& spans, std::size_t a, std::size_t b);

/// The graph's initial poses: the first mission's odometry as it is, each
/// later mission's carried into the world by alignMission over its loops
/// (query, match nodes) into the missions before it. Throws FormatError
/// naming the mission when it has no such loop (nothing places it).
pose_graph::PoseVector initialPoses(const std::vector<MissionSpan>& spans,
                                    const pose_graph::PoseVector& odometry,
                                    const std::vector<std::pair<std::size_t, std::size_t>>& loops);

/// Per later mission: its loops into earlier missions and its position
/// error against the truth in its own odometry frame, placed by its loops
/// and after the pose graph.
std::string missionReport(const std::vector<MissionSpan>& spans,
                          const std::vector<Eigen::Vector3d>& truth,
                          const std::vector<Eigen::Vector3d>& odometry,
                          const std::vector<Eigen::Vector3d>& placed,
                          const std::vector<Eigen::Vector3d>& optimised,
                          const std::vector<std::pair<std::size_t, std::size_t>>& loops);

}  // namespace pose_graph_app
}  // namespace bowg
