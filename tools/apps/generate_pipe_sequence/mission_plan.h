// The missions bowg_generate_pipe_sequence renders into one output: the
// first as the options say and, with --again, a second through the same
// network months later (docs/pipe_sequence.md, "Re-inspection sequences"):
// the same pipes, grain and permanent marks, a share of the unique marks
// replaced, its own roll, exposure, noise, speed, odometry and route.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bowg_pipe_sim/odometry_model.h"
#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/wall_texture.h"
#include "generator_args.h"

namespace bowg {
namespace generate_pipe_sequence_app {

struct MissionPlan {
  int id = 1;
  std::string name;  ///< missions.csv's name: "first survey", "second survey"
  std::vector<int> route_nodes;
  std::string route_flag;              ///< the flag that gave a custom node list, for its errors
  pipe_sim::SequenceOptions sequence;  ///< start_stamp: set by planFrames
  pipe_sim::WallTextureOptions texture;
  pipe_sim::OdometryNoise odometry;
};

/// The first mission and, with --again, the second. The texture options
/// hold args.texture's grain images: load them before.
std::vector<MissionPlan> planMissions(const Args& args);

/// The mission's route; a custom node list's errors (not joined, U-turn, no
/// such node) name the flag that gave it.
pipe_sim::Route makeRoute(const pipe_sim::PipeNetwork& network, const MissionPlan& mission);

/// The frames of `mission` along `route`, continuing `previous` (the frames
/// of the missions before): frame numbers and the odometer (metres driven)
/// go on, the first stamp is one frame period after the last; `distance`
/// (the position along the route) is the mission's own.
std::vector<pipe_sim::FrameState> planFrames(const pipe_sim::Route& route, MissionPlan mission,
                                             const std::vector<pipe_sim::FrameState>& previous);

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
