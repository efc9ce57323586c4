// bowg_pose_graph's command line.
#pragma once

#include <string>

#include "bowg_pose_graph/pose_graph.h"

namespace bowg {
namespace pose_graph_app {

struct Args {
  std::string truth;     ///< --truth: true body poses (the generator's poses.csv)
  std::string odometry;  ///< --odometry: drifting odometry (the generator's odometry.csv)
  std::string loops;     ///< --loops: bowg_evaluate's detections_<row>.csv (query,match,score)
  /// --loop-poses: bowg_evaluate's loop_poses_<row>.csv; loops with a metric
  /// translation become metric edges (camera at the body's origin, looking
  /// along x: the generator's camera).
  std::string loop_poses;
  std::string output;  ///< --output DIR: trajectories.csv, summary.txt, trajectories.png
  /// --missions: where each survey starts (the generator's missions.csv):
  /// each has an odometry frame of its own (mission_frames.h).
  std::string missions;
  pose_graph::PoseGraphOptions graph;
};

extern const char* const kUsage;

/// Throws std::invalid_argument with a message for the user (exit 2).
Args parseArgs(int argc, char** argv);

}  // namespace pose_graph_app
}  // namespace bowg
