// bowg_generate_pipe_sequence's command line: the usage text, the options
// and their parser (with the checks across options and the derived
// defaults: focal length, principal point, ground-truth path, odometry seed,
// the second mission's seed and speed).
#pragma once

#include <cstdint>
#include <string>

#include "bowg_evaluation/ground_truth.h"
#include "bowg_pipe_sim/odometry_model.h"
#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/wall_texture.h"

namespace bowg {
namespace generate_pipe_sequence_app {

extern const char* const kUsage;

/// The second mission (--again, --again-*): the same network inspected again
/// months later, rendered after the first into the same output.
struct AgainArgs {
  bool enabled = false;        ///< --again, or any --again-* option
  double marks_changed = 0.2;  ///< share of the unique marks replaced, [0, 1]
  std::uint64_t seed = 0;      ///< roll, exposure, noise, odometry, new marks
  bool seed_given = false;     ///< else --seed + 1000
  double speed_mps = 0;        ///< else --speed
  std::string route_nodes;     ///< empty: the first mission's route
};

struct Args {
  std::string bag, images, gt, compression = "none", bag_images = "mono8";
  std::string route = "figure-eight", route_nodes, texture_images;
  double texture_crop = 0.15;
  bool texture_crop_given = false, route_given = false;
  pipe_sim::SequenceOptions sequence;
  pipe_sim::WallTextureOptions texture;
  pipe_sim::CameraModel camera;
  eval::GroundTruthOptions gt_options;
  pipe_sim::OdometryNoise odometry;  ///< its seed derived from --seed
  AgainArgs again;
};

/// The bag's path without ".bag": the stem of the files written beside it.
std::string bagStem(const std::string& bag);

/// Throws std::invalid_argument naming the flag (see kUsage); prints the
/// usage and exits 0 on -h/--help.
Args parseArgs(int argc, char** argv);

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
