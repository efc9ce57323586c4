// bowg_generate_pipe_sequence: renders the in-pipe sequence (see
// docs/pipe_sequence.md) into a rosbag and/or a PNG folder, plus the loop
// ground truth computed from the poses.
//
//   rosrun bowg_ros bowg_generate_pipe_sequence --bag pipe.bag [--images DIR]
//       [--gt pipe_gt.txt] [--laps 1] [--frames N] [--seed 1] [--width 640]
//       [--height 480] [--fx 320] [--roll-amplitude 60] [--marks-per-metre 1]
//       [--grain-repeat 0.5] [--texture-images DIR [--texture-crop 0.15]]
//       [--route figure-eight|circuit|partial|no-revisit | --route-nodes 0,1,...]
//       [--network-width 4] [--network-height 3] [--roll-knot-spacing 3]
//       [--exposure-variation 0.2] [--exposure-step 0.15]
//       [--speed 0.2] [--rate 10] [--speed-variation 0] [--speed-knot-seconds 4]
//       [--allow-reverse] [--gt-distance 0.15] [--gt-heading 30]
//       [--gt-exclude 3] [--compression none|lz4|bz2]
//       [--odometry-slip 0.03] [--odometry-slip-noise 0.02]
//       [--odometry-heading-drift 1] [--odometry-roll-drift 1]
//       [--again] [--again-marks-changed 0.2] [--again-seed N]
//       [--again-speed MPS] [--again-route-nodes 0,1,...]
//
// The pieces: generator_args (command line), mission_plan (the missions:
// one, or two through the same network with --again), sequence_outputs (the
// bag via bag_output, the PNG files, poses.csv, the drifting odometry,
// missions.csv), ground_truth_report (the loop ground truth and its header);
// here the scene, the render loop and the console summary.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/quilted_grain.h"
#include "bowg_pipe_sim/wall_texture.h"
#include "generator_args.h"
#include "ground_truth_report.h"
#include "mission_plan.h"
#include "sequence_outputs.h"

namespace bowg {
namespace generate_pipe_sequence_app {
namespace {

using namespace bowg::pipe_sim;

struct RenderTime {
  double total_ms = 0, max_ms = 0;
};

/// Renders every frame into `outputs`, with a progress line on stderr;
/// adds to `time`.
void renderFrames(const PipeRenderer& renderer, const std::vector<FrameState>& frames,
                  std::uint64_t seed, SequenceOutputs* outputs, RenderTime* time_sum) {
  RenderTime& time = *time_sum;
  for (const FrameState& f : frames) {
    const auto t0 = std::chrono::steady_clock::now();
    const cv::Mat image = renderer.render(f.pose, f.exposure, seed * 1000003ULL + f.index);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    time.total_ms += ms;
    time.max_ms = std::max(time.max_ms, ms);
    outputs->add(f, image);
    const int done = f.index - frames.front().index + 1;
    if (f.index % 20 == 0 || done == static_cast<int>(frames.size())) {
      std::fprintf(stderr, "\rrendering %d/%zu", done, frames.size());
    }
  }
  std::fprintf(stderr, "\n");
}

/// One mission's drive: its route and frames, planned before anything is
/// rendered so that a bad route of the second mission stops the run early.
struct MissionDrive {
  MissionPlan plan;
  Route route;
  std::vector<FrameState> frames;
};

std::vector<MissionDrive> planDrives(const PipeNetwork& network, const Args& args) {
  std::vector<MissionDrive> drives;
  std::vector<FrameState> previous;
  for (const MissionPlan& plan : planMissions(args)) {
    Route route = makeRoute(network, plan);
    std::vector<FrameState> frames = planFrames(route, plan, previous);
    previous = frames;
    drives.push_back(MissionDrive{plan, std::move(route), std::move(frames)});
  }
  return drives;
}

/// Renders every mission into `outputs`, each with its own texture (the
/// second's marks changed) and renderer; returns all frames in order and
/// the first frame of each mission.
std::vector<FrameState> renderMissions(const PipeNetwork& network, const Args& args,
                                       const std::vector<MissionDrive>& drives,
                                       SequenceOutputs* outputs, RenderTime* time,
                                       std::vector<int>* starts) {
  std::vector<FrameState> all;
  for (const MissionDrive& d : drives) {
    const WallTexture texture(network, d.plan.texture);
    const PipeRenderer renderer(network, d.route, texture, args.camera, LightModel(),
                                SensorModel());
    starts->push_back(d.frames.front().index);
    outputs->startMission(d.frames.front().index, d.plan.id, d.plan.name, d.plan.odometry);
    renderFrames(renderer, d.frames, d.plan.sequence.seed, outputs, time);
    all.insert(all.end(), d.frames.begin(), d.frames.end());
  }
  return all;
}

int run(int argc, char** argv) {
  Args args = parseArgs(argc, argv);
  const PipeNetwork network = PipeNetwork::figureEight(args.sequence.network_width_m,
                                                       args.sequence.network_height_m);
  if (!args.texture_images.empty()) {
    args.texture.grain_images = loadGrainImages(args.texture_images, args.texture_crop);
  }
  const std::vector<MissionDrive> drives = planDrives(network, args);

  SequenceOutputs outputs(args);
  RenderTime time;
  std::vector<int> starts;
  const std::vector<FrameState> frames =
      renderMissions(network, args, drives, &outputs, &time, &starts);
  outputs.finish();
  const GroundTruthSummary gt =
      writeSequenceGroundTruth(args, frames, starts, outputs.travel(), outputs.odometryDrift());

  std::printf("frames: %zu, %s\n", frames.size(), gt.spacing.c_str());
  std::printf("render: %.1f ms mean, %.1f ms max per %dx%d frame\n", time.total_ms / frames.size(),
              time.max_ms, args.camera.width, args.camera.height);
  std::printf("ground truth: %d queries with a revisit, median roll difference %.1f deg -> %s\n",
              gt.positives, gt.median_roll_deg, args.gt.c_str());
  std::printf("odometry: %s\n", gt.odometry.c_str());
  if (starts.size() > 1) {
    std::printf("missions: 2, the second survey from frame %d (missions.csv)\n", starts[1]);
  }
  if (!args.bag.empty()) std::printf("bag: %s\n", args.bag.c_str());
  if (!args.images.empty()) std::printf("images: %s\n", args.images.c_str());
  return 0;
}

}  // namespace
}  // namespace generate_pipe_sequence_app
}  // namespace bowg

int main(int argc, char** argv) {
  try {
    return bowg::generate_pipe_sequence_app::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bowg_generate_pipe_sequence: %s\n", e.what());
    return 1;
  }
}
