// bowg_generate_pipe_sequence's command line (generator_args.h): the usage
// text, the number parsers that name the flag in their errors, and the
// parser itself.
#include "generator_args.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bowg_evaluation/command_line.h"
#include "bowg_pipe_sim/random.h"
#include "bowg_pipe_sim/route_programs.h"

namespace bowg {
namespace generate_pipe_sequence_app {

const char* const kUsage =
    "usage: bowg_generate_pipe_sequence (--bag FILE | --images DIR) [options]\n"
    "  --bag FILE             write a rosbag: /camera/image_raw (mono8), /camera/camera_info,\n"
    "                         /ground_truth/pose (geometry_msgs/PoseStamped, frame map),\n"
    "                         /ground_truth/odom (the same as nav_msgs/Odometry),\n"
    "                         /odom (nav_msgs/Odometry, the drifting odometry, frame odom)\n"
    "  --bag-images FORMAT    the bag's images: mono8, bgr8 (the grey image in three\n"
    "                         channels) or jpeg (sensor_msgs/CompressedImage on\n"
    "                         /camera/image_raw/compressed, quality 95) [mono8]\n"
    "  --images DIR           write frame_000000.png ... (and poses.csv, odometry.csv) into DIR\n"
    "  --gt FILE              ground-truth loops (default: <bag>_gt.txt or DIR/ground_truth.txt)\n"
    "  --route NAME           figure-eight, circuit, partial or no-revisit "
    "(docs/pipe_sequence.md)\n"
    "                         [figure-eight]\n"
    "  --route-nodes LIST     a custom route instead: node indices 0-5, e.g. 0,1,4,5,0,1\n"
    "  --laps N               laps of the route (figure-eight: 48 m of pipe each; circuit) [1]\n"
    "  --network-width M --network-height M\n"
    "                         size of the network's rectangle [4 3]\n"
    "  --frames N             stop after N frames (0 = whole route) [0]\n"
    "  --seed N               texture, roll, exposure and noise seed [1]\n"
    "  --width W --height H   image size [640 480]\n"
    "  --fx F                 focal length in px (fy = fx, principal point at the centre) [W/2]\n"
    "  --roll-amplitude DEG   roll about the pipe axis in [-DEG, DEG] [60]\n"
    "  --roll-knot-spacing M  metres of driving between the roll's random knots [3]\n"
    "  --exposure-variation X --exposure-step X\n"
    "                         auto exposure: smooth log-gain range and 8 s steps [0.2 0.15]\n"
    "  --marks-per-metre X    unique wall marks per metre (texture repetitiveness) [1]\n"
    "  --grain-repeat G       fraction of the wall grain repeated in every section, in [0, 1]\n"
    "                         (1 = pixel-identical sections, 0 = no shared grain) [0.5]\n"
    "  --texture-images DIR   quilt the wall grain from the PNG/JPG images in DIR [procedural]\n"
    "  --texture-crop F       fraction of rows cut from the top and the bottom of those\n"
    "                         images (text overlays) [0.15]\n"
    "  --speed MPS --rate HZ  mean driving speed and frame rate [0.2 10]\n"
    "  --speed-variation V    speed * (1 + V * smooth noise in [-1, 1]) [0 = constant]\n"
    "  --speed-knot-seconds S seconds between the speed noise's knots [4]\n"
    "  --allow-reverse        back up where the speed is negative (no value; default: stop)\n"
    "  --odometry-slip F      fraction of the distance the odometry over-reports (wheel slip,\n"
    "                         tether stretch; negative: under-reports), in [-0.5, 0.5] [0.03]\n"
    "  --odometry-slip-noise F\n"
    "                         relative sigma of each frame's distance, >= 0 [0.02]\n"
    "  --odometry-heading-drift DEG --odometry-roll-drift DEG\n"
    "                         odometry's random walk of yaw and pitch / of roll, sigma in deg\n"
    "                         per sqrt(metre driven), >= 0 [1 1]\n"
    "  --gt-distance M --gt-heading DEG --gt-exclude M\n"
    "                         ground-truth tolerances [0.15 30 3]\n"
    "  --compression C        bag compression: none, lz4 or bz2 (noisy images hardly\n"
    "                         compress) [none]\n"
    "re-inspection: a second mission through the same network after the first, into the\n"
    "same output (frames, poses.csv, odometry.csv and stamps continue; missions.csv says\n"
    "where each mission starts; the second mission's odometry starts a new frame):\n"
    "  --again                render the second mission (no value; implied by any --again-*)\n"
    "  --again-marks-changed F\n"
    "                         share of the unique wall marks removed and replaced by as many\n"
    "                         new ones at random places, in [0, 1] [0.2]\n"
    "  --again-seed N         the second mission's roll, exposure, image noise, odometry\n"
    "                         noise and new marks [--seed + 1000]\n"
    "  --again-speed MPS      its mean driving speed, > 0 [--speed]\n"
    "  --again-route-nodes LIST\n"
    "                         its own route, node indices as --route-nodes (e.g. the first\n"
    "                         route reversed) [the first mission's route]\n"
    "  (--frames N stops each mission after N frames; the other options apply to both)\n";

namespace {

/// For the options without a field check of their own: the message names
/// the flag, not the struct field.
double atLeast(const std::string& flag, const std::string& value, double low, bool inclusive) {
  const double v = eval::numberArgument(flag, value);
  if (inclusive ? v < low : v <= low) {
    std::ostringstream message;
    message << flag << " must be " << (inclusive ? ">= " : "> ") << low << ", not " << value;
    throw std::invalid_argument(message.str());
  }
  return v;
}

int toInt(const std::string& flag, const std::string& value) {
  const double v = eval::numberArgument(flag, value);
  if (v != std::floor(v) || std::abs(v) > 1e9) {
    throw std::invalid_argument(flag + ": '" + value + "' is not an integer");
  }
  return static_cast<int>(v);
}

/// The options of the drive alone (route length, roll, exposure, speed);
/// false for any other flag.
bool setSequenceOption(pipe_sim::SequenceOptions* s, const std::string& flag,
                       const std::string& v) {
  if (flag == "--laps") s->laps = toInt(flag, v);
  else if (flag == "--frames") s->max_frames = toInt(flag, v);
  else if (flag == "--roll-amplitude") s->roll_amplitude_deg = eval::numberArgument(flag, v);
  else if (flag == "--speed") s->speed_mps = atLeast(flag, v, 0, false);
  else if (flag == "--rate") s->frame_rate_hz = eval::numberArgument(flag, v);
  else if (flag == "--speed-variation") s->speed_variation = atLeast(flag, v, 0, true);
  else if (flag == "--speed-knot-seconds") s->speed_knot_s = atLeast(flag, v, 0, false);
  else if (flag == "--network-width") s->network_width_m = atLeast(flag, v, 0, false);
  else if (flag == "--network-height") s->network_height_m = atLeast(flag, v, 0, false);
  else if (flag == "--roll-knot-spacing") s->roll_knot_spacing_m = atLeast(flag, v, 0, false);
  else if (flag == "--exposure-variation") s->exposure_variation = atLeast(flag, v, 0, true);
  else if (flag == "--exposure-step") s->exposure_step = atLeast(flag, v, 0, true);
  else return false;
  return true;
}

/// The odometry's options; false for any other flag.
bool setOdometryOption(pipe_sim::OdometryNoise* o, const std::string& flag,
                       const std::string& v) {
  if (flag == "--odometry-slip") {
    o->scale_bias = eval::numberArgument(flag, v);
    if (!(o->scale_bias >= -0.5 && o->scale_bias <= 0.5)) {
      throw std::invalid_argument("--odometry-slip must be in [-0.5, 0.5], not " + v);
    }
  } else if (flag == "--odometry-slip-noise") o->scale_noise = atLeast(flag, v, 0, true);
  else if (flag == "--odometry-heading-drift") o->heading_drift_deg = atLeast(flag, v, 0, true);
  else if (flag == "--odometry-roll-drift") o->roll_drift_deg = atLeast(flag, v, 0, true);
  else return false;
  return true;
}

/// The second mission's options (--again-*); false for any other flag.
bool setAgainOption(AgainArgs* a, const std::string& flag, const std::string& v) {
  if (flag == "--again-marks-changed") {
    a->marks_changed = eval::numberArgument(flag, v);
    if (!(a->marks_changed >= 0 && a->marks_changed <= 1)) {
      throw std::invalid_argument("--again-marks-changed must be in [0, 1], not " + v);
    }
  } else if (flag == "--again-seed") {
    const int seed = toInt(flag, v);
    if (seed < 0) throw std::invalid_argument("--again-seed must be >= 0, not " + v);
    a->seed = static_cast<std::uint64_t>(seed);
    a->seed_given = true;
  } else if (flag == "--again-speed") a->speed_mps = atLeast(flag, v, 0, false);
  else if (flag == "--again-route-nodes") a->route_nodes = v;
  else return false;
  a->enabled = true;
  return true;
}

/// One option with its value; `fx` keeps --fx until the image size is known.
void setOption(Args* a, double* fx, const std::string& flag, const std::string& v) {
  if (setSequenceOption(&a->sequence, flag, v)) return;
  if (setOdometryOption(&a->odometry, flag, v)) return;
  if (setAgainOption(&a->again, flag, v)) return;
  if (flag == "--bag") a->bag = v;
  else if (flag == "--images") a->images = v;
  else if (flag == "--gt") a->gt = v;
  else if (flag == "--compression") a->compression = v;
  else if (flag == "--bag-images") {
    if (v != "mono8" && v != "bgr8" && v != "jpeg") {
      throw std::invalid_argument("--bag-images must be mono8, bgr8 or jpeg (got '" + v + "')");
    }
    a->bag_images = v;
  } else if (flag == "--seed") {
    const int seed = toInt(flag, v);
    if (seed < 0) throw std::invalid_argument("--seed must be >= 0");
    a->sequence.seed = a->texture.seed = static_cast<std::uint64_t>(seed);
  } else if (flag == "--width") a->camera.width = toInt(flag, v);
  else if (flag == "--height") a->camera.height = toInt(flag, v);
  else if (flag == "--fx") *fx = eval::numberArgument(flag, v);
  else if (flag == "--marks-per-metre") a->texture.marks_per_metre = eval::numberArgument(flag, v);
  else if (flag == "--grain-repeat") a->texture.grain_repeat = eval::numberArgument(flag, v);
  else if (flag == "--route") a->route = v, a->route_given = true;
  else if (flag == "--route-nodes") a->route_nodes = v;
  else if (flag == "--texture-images") a->texture_images = v;
  else if (flag == "--texture-crop") {
    a->texture_crop = eval::numberArgument(flag, v);
    a->texture_crop_given = true;
    if (!(a->texture_crop >= 0 && a->texture_crop <= 0.45)) {
      throw std::invalid_argument("--texture-crop must be in [0, 0.45], not " + v);
    }
  } else if (flag == "--gt-distance") a->gt_options.max_distance_m = eval::numberArgument(flag, v);
  else if (flag == "--gt-heading") a->gt_options.max_heading_deg = eval::numberArgument(flag, v);
  else if (flag == "--gt-exclude") a->gt_options.exclude_recent_m = eval::numberArgument(flag, v);
  else throw std::invalid_argument("unknown option " + flag + " (see --help)");
}

/// The checks across options, once all of them are read.
void checkCombinations(const Args& a) {
  if (a.bag.empty() && a.images.empty()) {
    throw std::invalid_argument("give --bag FILE and/or --images DIR (see --help)");
  }
  if (a.compression != "lz4" && a.compression != "bz2" && a.compression != "none") {
    throw std::invalid_argument("--compression must be lz4, bz2 or none, not " + a.compression);
  }
  const std::vector<std::string>& routes = pipe_sim::routeProgramNames();
  if (std::find(routes.begin(), routes.end(), a.route) == routes.end()) {
    throw std::invalid_argument(
        "--route must be figure-eight, circuit, partial or no-revisit, not " + a.route);
  }
  if (!a.route_nodes.empty() && a.route_given) {
    throw std::invalid_argument("give --route or --route-nodes, not both");
  }
  if (!a.route_nodes.empty() && a.sequence.laps != 1) {
    throw std::invalid_argument("--route-nodes is the whole route: --laps must be 1");
  }
  if ((a.route == "partial" || a.route == "no-revisit") && a.sequence.laps != 1) {
    throw std::invalid_argument("--route " + a.route + " is one mission: --laps must be 1");
  }
  if (a.texture_crop_given && a.texture_images.empty()) {
    throw std::invalid_argument("--texture-crop needs --texture-images");
  }
}

/// What follows from other options: the intrinsics from the image size (and
/// --fx), the ground truth's path from the outputs, the odometry's seed from
/// --seed, the second mission's seed and speed from the first's.
void deriveDefaults(Args* a, double fx) {
  // A stream of its own ("odom"): the odometry noise is not correlated with
  // the roll, speed or texture drawn from the same --seed.
  a->odometry.seed = pipe_sim::hashCombine(a->sequence.seed, 0x6f646f6dULL);
  a->camera.fx = a->camera.fy = fx > 0 ? fx : a->camera.width / 2.0;
  a->camera.cx = (a->camera.width - 1) / 2.0;
  a->camera.cy = (a->camera.height - 1) / 2.0;
  if (a->gt.empty()) {
    a->gt = !a->bag.empty() ? bagStem(a->bag) + "_gt.txt" : a->images + "/ground_truth.txt";
  }
  if (!a->again.seed_given) a->again.seed = a->sequence.seed + 1000;
  if (!(a->again.speed_mps > 0)) a->again.speed_mps = a->sequence.speed_mps;
}

}  // namespace

std::string bagStem(const std::string& bag) {
  return bag.size() > 4 && bag.substr(bag.size() - 4) == ".bag" ? bag.substr(0, bag.size() - 4)
                                                                : bag;
}

Args parseArgs(int argc, char** argv) {
  Args a;
  double fx = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "-h" || flag == "--help") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (flag == "--allow-reverse") {
      a.sequence.allow_reverse = true;
      continue;
    }
    if (flag == "--again") {
      a.again.enabled = true;
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(flag + ": missing value (see --help)");
    setOption(&a, &fx, flag, argv[++i]);
  }
  checkCombinations(a);
  deriveDefaults(&a, fx);
  a.sequence.validate();
  a.texture.validate();
  a.camera.validate();
  a.gt_options.validate();
  a.odometry.validate();
  return a;
}

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
