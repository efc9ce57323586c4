// The missions of one generated output (mission_plan.h): their options,
// routes and frames.
#include "mission_plan.h"

#include <stdexcept>

#include "bowg_pipe_sim/random.h"
#include "bowg_pipe_sim/route_programs.h"

namespace bowg {
namespace generate_pipe_sequence_app {
namespace {

using namespace bowg::pipe_sim;

MissionPlan firstMission(const Args& args) {
  MissionPlan m;
  m.id = 1;
  m.name = "first survey";
  if (args.route_nodes.empty()) {
    m.route_nodes = routeProgramNodes(args.route, args.sequence.laps);
  } else {
    m.route_nodes = parseRouteNodes(args.route_nodes, "--route-nodes");
    m.route_flag = "--route-nodes " + args.route_nodes;
  }
  m.sequence = args.sequence;
  m.texture = args.texture;
  m.odometry = args.odometry;
  return m;
}

/// The same network and wall, another drive: what is drawn from a seed
/// (roll, wobble, exposure, speed noise, image noise, odometry noise, the
/// new marks) is drawn from --again-seed; the grain and the permanent marks
/// stay those of --seed.
MissionPlan secondMission(const Args& args, const MissionPlan& first) {
  const AgainArgs& again = args.again;
  MissionPlan m = first;
  m.id = 2;
  m.name = "second survey";
  if (!again.route_nodes.empty()) {
    m.route_nodes = parseRouteNodes(again.route_nodes, "--again-route-nodes");
    m.route_flag = "--again-route-nodes " + again.route_nodes;
  }
  m.sequence.seed = again.seed;
  m.sequence.speed_mps = again.speed_mps;
  m.texture.marks_changed = again.marks_changed;
  m.texture.marks_change_seed = again.seed;
  // The first mission's odometry seed is derived from --seed the same way.
  m.odometry.seed = hashCombine(again.seed, 0x6f646f6dULL);
  return m;
}

}  // namespace

std::vector<MissionPlan> planMissions(const Args& args) {
  std::vector<MissionPlan> missions{firstMission(args)};
  if (args.again.enabled) missions.push_back(secondMission(args, missions.front()));
  return missions;
}

Route makeRoute(const PipeNetwork& network, const MissionPlan& mission) {
  try {
    return Route(network, mission.route_nodes, mission.sequence.bend_radius_m);
  } catch (const std::invalid_argument& e) {
    if (mission.route_flag.empty()) throw;
    throw std::invalid_argument(mission.route_flag + ": " + e.what());
  }
}

std::vector<FrameState> planFrames(const Route& route, MissionPlan mission,
                                   const std::vector<FrameState>& previous) {
  if (previous.empty()) return planSequence(route, mission.sequence);
  const FrameState& last = previous.back();
  mission.sequence.start_stamp = last.stamp + 1.0 / mission.sequence.frame_rate_hz;
  std::vector<FrameState> frames = planSequence(route, mission.sequence);
  for (FrameState& f : frames) {
    f.index += last.index + 1;
    // One odometer over the missions: the readers of poses.csv's odometer
    // column (and of the gaps the ground truth excludes) take metres driven
    // as never decreasing.
    f.odometer += last.odometer;
  }
  return frames;
}

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
