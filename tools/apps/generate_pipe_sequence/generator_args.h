// bowg_generate_pipe_sequence's command line: the usage text, the options
// and their parser (with the checks across options and the derived
// defaults: focal length, principal point, ground-truth path, odometry seed).
#pragma once

#include <string>

#include "bowg_evaluation/ground_truth.h"
#include "bowg_pipe_sim/odometry_model.h"
#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/wall_texture.h"

namespace bowg {
namespace generate_pipe_sequence_app {

extern const char* const kUsage;

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
};

/// Throws std::invalid_argument naming the flag (see kUsage); prints the
/// usage and exits 0 on -h/--help.
Args parseArgs(int argc, char** argv);

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
