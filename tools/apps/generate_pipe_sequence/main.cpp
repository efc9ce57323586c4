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
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>
#include <std_msgs/Header.h>

#include "bowg/core/atomic_file.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/quilted_grain.h"
#include "bowg_pipe_sim/route_programs.h"
#include "bowg_pipe_sim/sequence_stats.h"
#include "bowg_pipe_sim/wall_texture.h"

namespace {

using namespace bowg;
using namespace bowg::pipe_sim;

const char* kUsage =
    "usage: bowg_generate_pipe_sequence (--bag FILE | --images DIR) [options]\n"
    "  --bag FILE             write a rosbag: /camera/image_raw (mono8), /camera/camera_info,\n"
    "                         /ground_truth/pose (geometry_msgs/PoseStamped, frame map)\n"
    "  --bag-images FORMAT    the bag's images: mono8, bgr8 (the grey image in three\n"
    "                         channels) or jpeg (sensor_msgs/CompressedImage on\n"
    "                         /camera/image_raw/compressed, quality 95) [mono8]\n"
    "  --images DIR           write frame_000000.png ... (and poses.csv) into DIR\n"
    "  --gt FILE              ground-truth loops (default: <bag>_gt.txt or DIR/ground_truth.txt)\n"
    "  --route NAME           figure-eight, circuit, partial or no-revisit (docs/pipe_sequence.md)\n"
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
    "  --gt-distance M --gt-heading DEG --gt-exclude M\n"
    "                         ground-truth tolerances [0.15 30 3]\n"
    "  --compression C        bag compression: none, lz4 or bz2 (noisy images hardly\n"
    "                         compress) [none]\n";

struct Args {
  std::string bag, images, gt, compression = "none", bag_images = "mono8";
  std::string route = "figure-eight", route_nodes, texture_images;
  double texture_crop = 0.15;
  bool texture_crop_given = false, route_given = false;
  SequenceOptions sequence;
  WallTextureOptions texture;
  CameraModel camera;
  eval::GroundTruthOptions gt_options;
};

// One frame into the bag in the chosen format (--bag-images); every format
// holds the same grey image (bgr8: three equal channels, which OpenCV's luma
// weights turn back into the same grey; jpeg: lossy, decoded alike live and
// offline).
void writeBagImage(rosbag::Bag* bag, const std_msgs::Header& header, const cv::Mat& grey,
                   const std::string& format) {
  if (format == "jpeg") {
    sensor_msgs::CompressedImage msg;
    msg.header = header;
    msg.format = "mono8; jpeg compressed mono8";
    if (!cv::imencode(".jpg", grey, msg.data, {cv::IMWRITE_JPEG_QUALITY, 95})) {
      throw std::runtime_error("cannot encode frame " + std::to_string(header.seq) + " as JPEG");
    }
    bag->write("/camera/image_raw/compressed", header.stamp, msg);
    return;
  }
  cv::Mat pixels = grey;
  if (format == "bgr8") cv::cvtColor(grey, pixels, cv::COLOR_GRAY2BGR);
  sensor_msgs::Image msg;
  msg.header = header;
  msg.height = pixels.rows;
  msg.width = pixels.cols;
  msg.encoding = format == "bgr8" ? sensor_msgs::image_encodings::BGR8
                                  : sensor_msgs::image_encodings::MONO8;
  msg.is_bigendian = 0;
  msg.step = static_cast<std::uint32_t>(pixels.cols * pixels.elemSize());
  const cv::Mat packed = pixels.isContinuous() ? pixels : pixels.clone();
  msg.data.assign(packed.data, packed.data + packed.total() * packed.elemSize());
  bag->write("/camera/image_raw", header.stamp, msg);
}

double toNumber(const std::string& flag, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v)) {
    throw std::invalid_argument(flag + ": '" + value + "' is not a number");
  }
  return v;
}

/// For the options without a field check of their own: the message names
/// the flag, not the struct field.
double atLeast(const std::string& flag, const std::string& value, double low, bool inclusive) {
  const double v = toNumber(flag, value);
  if (inclusive ? v < low : v <= low) {
    std::ostringstream message;
    message << flag << " must be " << (inclusive ? ">= " : "> ") << low << ", not " << value;
    throw std::invalid_argument(message.str());
  }
  return v;
}

int toInt(const std::string& flag, const std::string& value) {
  const double v = toNumber(flag, value);
  if (v != std::floor(v) || std::abs(v) > 1e9) {
    throw std::invalid_argument(flag + ": '" + value + "' is not an integer");
  }
  return static_cast<int>(v);
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
    if (i + 1 >= argc) throw std::invalid_argument(flag + ": missing value (see --help)");
    const std::string v = argv[++i];
    if (flag == "--bag") a.bag = v;
    else if (flag == "--images") a.images = v;
    else if (flag == "--gt") a.gt = v;
    else if (flag == "--compression") a.compression = v;
    else if (flag == "--bag-images") {
      if (v != "mono8" && v != "bgr8" && v != "jpeg") {
        throw std::invalid_argument("--bag-images must be mono8, bgr8 or jpeg (got '" + v + "')");
      }
      a.bag_images = v;
    }
    else if (flag == "--laps") a.sequence.laps = toInt(flag, v);
    else if (flag == "--frames") a.sequence.max_frames = toInt(flag, v);
    else if (flag == "--seed") {
      const int seed = toInt(flag, v);
      if (seed < 0) throw std::invalid_argument("--seed must be >= 0");
      a.sequence.seed = a.texture.seed = static_cast<std::uint64_t>(seed);
    } else if (flag == "--width") a.camera.width = toInt(flag, v);
    else if (flag == "--height") a.camera.height = toInt(flag, v);
    else if (flag == "--fx") fx = toNumber(flag, v);
    else if (flag == "--roll-amplitude") a.sequence.roll_amplitude_deg = toNumber(flag, v);
    else if (flag == "--marks-per-metre") a.texture.marks_per_metre = toNumber(flag, v);
    else if (flag == "--grain-repeat") a.texture.grain_repeat = toNumber(flag, v);
    else if (flag == "--speed") a.sequence.speed_mps = toNumber(flag, v);
    else if (flag == "--rate") a.sequence.frame_rate_hz = toNumber(flag, v);
    else if (flag == "--speed-variation") a.sequence.speed_variation = atLeast(flag, v, 0, true);
    else if (flag == "--speed-knot-seconds") a.sequence.speed_knot_s = atLeast(flag, v, 0, false);
    else if (flag == "--route") a.route = v, a.route_given = true;
    else if (flag == "--route-nodes") a.route_nodes = v;
    else if (flag == "--network-width") a.sequence.network_width_m = atLeast(flag, v, 0, false);
    else if (flag == "--network-height") a.sequence.network_height_m = atLeast(flag, v, 0, false);
    else if (flag == "--roll-knot-spacing") a.sequence.roll_knot_spacing_m = atLeast(flag, v, 0, false);
    else if (flag == "--exposure-variation") a.sequence.exposure_variation = atLeast(flag, v, 0, true);
    else if (flag == "--exposure-step") a.sequence.exposure_step = atLeast(flag, v, 0, true);
    else if (flag == "--texture-images") a.texture_images = v;
    else if (flag == "--texture-crop") {
      a.texture_crop = toNumber(flag, v);
      a.texture_crop_given = true;
      if (!(a.texture_crop >= 0 && a.texture_crop <= 0.45)) {
        throw std::invalid_argument("--texture-crop must be in [0, 0.45], not " + v);
      }
    }
    else if (flag == "--gt-distance") a.gt_options.max_distance_m = toNumber(flag, v);
    else if (flag == "--gt-heading") a.gt_options.max_heading_deg = toNumber(flag, v);
    else if (flag == "--gt-exclude") a.gt_options.exclude_recent_m = toNumber(flag, v);
    else throw std::invalid_argument("unknown option " + flag + " (see --help)");
  }
  if (a.bag.empty() && a.images.empty()) {
    throw std::invalid_argument("give --bag FILE and/or --images DIR (see --help)");
  }
  if (a.compression != "lz4" && a.compression != "bz2" && a.compression != "none") {
    throw std::invalid_argument("--compression must be lz4, bz2 or none, not " + a.compression);
  }
  if (std::find(routeProgramNames().begin(), routeProgramNames().end(), a.route) ==
      routeProgramNames().end()) {
    throw std::invalid_argument("--route must be figure-eight, circuit, partial or no-revisit, not " + a.route);
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
  a.camera.fx = a.camera.fy = fx > 0 ? fx : a.camera.width / 2.0;
  a.camera.cx = (a.camera.width - 1) / 2.0;
  a.camera.cy = (a.camera.height - 1) / 2.0;
  if (a.gt.empty()) {
    if (!a.bag.empty()) {
      const std::string stem =
          a.bag.size() > 4 && a.bag.substr(a.bag.size() - 4) == ".bag" ? a.bag.substr(0, a.bag.size() - 4) : a.bag;
      a.gt = stem + "_gt.txt";
    } else {
      a.gt = a.images + "/ground_truth.txt";
    }
  }
  a.sequence.validate();
  a.texture.validate();
  a.camera.validate();
  a.gt_options.validate();
  return a;
}

ros::Time stampOf(double seconds) {
  ros::Time t;
  t.fromSec(seconds);
  return t;
}

double wrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

std::vector<int> routeNodesOf(const Args& args) {
  if (args.route_nodes.empty()) return routeProgramNodes(args.route, args.sequence.laps);
  return parseRouteNodes(args.route_nodes, "--route-nodes");
}

/// The route, with a custom node list's errors (not joined, U-turn, no such
/// node) attributed to the flag that gave it.
Route makeRoute(const PipeNetwork& network, const Args& args) {
  try {
    return Route(network, routeNodesOf(args), args.sequence.bend_radius_m);
  } catch (const std::invalid_argument& e) {
    if (args.route_nodes.empty()) throw;
    throw std::invalid_argument("--route-nodes " + args.route_nodes + ": " + e.what());
  }
}

int run(int argc, char** argv) {
  Args args = parseArgs(argc, argv);
  const PipeNetwork network = PipeNetwork::figureEight(args.sequence.network_width_m,
                                                       args.sequence.network_height_m);
  const Route route = makeRoute(network, args);
  const std::vector<FrameState> frames = planSequence(route, args.sequence);
  if (!args.texture_images.empty()) {
    args.texture.grain_images = loadGrainImages(args.texture_images, args.texture_crop);
  }
  const WallTexture texture(network, args.texture);
  const PipeRenderer renderer(network, route, texture, args.camera, LightModel(), SensorModel());

  if (!args.images.empty()) {
    ::mkdir(args.images.c_str(), 0755);
    struct stat st;
    if (::stat(args.images.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
      throw std::runtime_error("cannot create the image folder " + args.images);
    }
  }
  rosbag::Bag bag;
  const std::string bag_tmp = args.bag + ".tmp";
  if (!args.bag.empty()) {
    bag.open(bag_tmp, rosbag::bagmode::Write);
    bag.setCompression(args.compression == "lz4"   ? rosbag::compression::LZ4
                       : args.compression == "bz2" ? rosbag::compression::BZ2
                                                   : rosbag::compression::Uncompressed);
  }

  sensor_msgs::CameraInfo info;
  info.header.frame_id = "camera_optical_frame";
  info.width = args.camera.width;
  info.height = args.camera.height;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {args.camera.fx, 0, args.camera.cx, 0, args.camera.fy, args.camera.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {args.camera.fx, 0, args.camera.cx, 0, 0, args.camera.fy, args.camera.cy, 0, 0, 0, 1, 0};

  std::ostringstream poses_csv;
  // distance: position along the route; odometer: metres driven (they differ
  // once the robot backs up).
  poses_csv << "frame,stamp,x,y,z,qx,qy,qz,qw,roll_deg,exposure,distance,odometer\n";
  std::vector<eval::TravelPose> travel;
  double render_ms = 0, max_render_ms = 0;
  for (const FrameState& f : frames) {
    const auto t0 = std::chrono::steady_clock::now();
    const cv::Mat image = renderer.render(f.pose, f.exposure, args.sequence.seed * 1000003ULL + f.index);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    render_ms += ms;
    max_render_ms = std::max(max_render_ms, ms);
    const cv::Vec4d q = rotationToQuaternion(f.pose.R_world_body);
    if (!args.bag.empty()) {
      const ros::Time stamp = stampOf(f.stamp);
      std_msgs::Header header;
      header.seq = f.index;
      header.stamp = stamp;
      header.frame_id = info.header.frame_id;
      writeBagImage(&bag, header, image, args.bag_images);
      info.header.seq = f.index;
      info.header.stamp = stamp;
      geometry_msgs::PoseStamped pose;
      pose.header.seq = f.index;
      pose.header.stamp = stamp;
      pose.header.frame_id = "map";
      pose.pose.position.x = f.pose.position[0];
      pose.pose.position.y = f.pose.position[1];
      pose.pose.position.z = f.pose.position[2];
      pose.pose.orientation.x = q[0];
      pose.pose.orientation.y = q[1];
      pose.pose.orientation.z = q[2];
      pose.pose.orientation.w = q[3];
      bag.write("/camera/camera_info", stamp, info);
      bag.write("/ground_truth/pose", stamp, pose);
    }
    if (!args.images.empty()) {
      char name[32];
      std::snprintf(name, sizeof(name), "/frame_%06d.png", f.index);
      if (!cv::imwrite(args.images + name, image)) {
        throw std::runtime_error("cannot write " + args.images + name);
      }
    }
    poses_csv << f.index << "," << std::fixed << f.stamp << "," << f.pose.position[0] << ","
              << f.pose.position[1] << "," << f.pose.position[2] << "," << q[0] << "," << q[1] << ","
              << q[2] << "," << q[3] << "," << f.roll_rad * 180 / M_PI << "," << f.exposure << ","
              << f.distance << "," << f.odometer << "\n";
    eval::TravelPose tp;
    tp.x = f.pose.position[0];
    tp.y = f.pose.position[1];
    tp.z = f.pose.position[2];
    tp.hx = f.tangent[0];
    tp.hy = f.tangent[1];
    tp.hz = f.tangent[2];
    // The ground truth's "immediate past" is metres driven: backing up 1 m
    // and coming forward again is 2 m, not 0.
    tp.distance = f.odometer;
    travel.push_back(tp);
    if (f.index % 20 == 0 || f.index + 1 == static_cast<int>(frames.size())) {
      std::fprintf(stderr, "\rrendering %d/%zu", f.index + 1, frames.size());
    }
  }
  std::fprintf(stderr, "\n");
  if (!args.bag.empty()) {
    bag.close();
    if (std::rename(bag_tmp.c_str(), args.bag.c_str()) != 0) {
      throw std::runtime_error("cannot rename " + bag_tmp + " to " + args.bag);
    }
  }
  if (!args.images.empty()) bowg::writeFileAtomically(args.images + "/poses.csv", poses_csv.str());

  const eval::GroundTruth gt = eval::groundTruthFromPoses(travel, args.gt_options);
  std::vector<double> roll_differences;
  for (const auto& kv : gt.loops) {
    for (int m : kv.second) {
      roll_differences.push_back(
          std::abs(wrapAngle(frames[kv.first].roll_rad - frames[m].roll_rad)) * 180 / M_PI);
    }
  }
  const double median_roll = median(roll_differences);
  const SequenceStats stats = sequenceStats(frames);
  const std::string route_name = args.route_nodes.empty() ? args.route : "nodes " + args.route_nodes;
  char spacing[160];
  std::snprintf(spacing, sizeof(spacing),
                "%.1f m driven (odometer), frame spacing min %.2f / median %.2f / max %.2f cm",
                stats.driven_m, 100 * stats.spacing_min_m, 100 * stats.spacing_median_m,
                100 * stats.spacing_max_m);
  std::ostringstream header;
  header << "bowg_ros pipe sequence ground truth (docs/pipe_sequence.md)\n"
         << "query: matches; 0-based index of the image messages (frames)\n"
         << "frames " << frames.size() << ", seed " << args.sequence.seed << ", laps "
         << args.sequence.laps << ", marks_per_metre " << args.texture.marks_per_metre
         << ", grain_repeat " << args.texture.grain_repeat
         << ", roll_amplitude_deg " << args.sequence.roll_amplitude_deg << "\n"
         << "route " << route_name << ", network " << args.sequence.network_width_m << " x "
         << args.sequence.network_height_m << " m, roll_knot_spacing_m "
         << args.sequence.roll_knot_spacing_m << ", exposure_variation "
         << args.sequence.exposure_variation << ", exposure_step " << args.sequence.exposure_step << "\n"
         << "speed " << args.sequence.speed_mps << " m/s, rate " << args.sequence.frame_rate_hz
         << " Hz, speed_variation " << args.sequence.speed_variation << ", speed_knot_seconds "
         << args.sequence.speed_knot_s << ", allow_reverse " << (args.sequence.allow_reverse ? "yes" : "no")
         << "\n"
         << "texture "
         << (args.texture_images.empty() ? "procedural" : "quilted from the images in " + args.texture_images);
  if (!args.texture_images.empty()) {
    header << " (" << args.texture.grain_images.size() << " images, crop " << args.texture_crop << ")";
  }
  header << "\n"
         << spacing << "\n"
         << "tolerances: distance < " << args.gt_options.max_distance_m << " m, heading < "
         << args.gt_options.max_heading_deg << " deg, excluding the last "
         << args.gt_options.exclude_recent_m << " m driven\n"
         << "queries with a revisit " << gt.positives() << ", median roll difference "
         << median_roll << " deg";
  eval::writeGroundTruth(args.gt, gt, header.str());

  std::printf("frames: %zu, %s\n", frames.size(), spacing);
  std::printf("render: %.1f ms mean, %.1f ms max per %dx%d frame\n", render_ms / frames.size(),
              max_render_ms, args.camera.width, args.camera.height);
  std::printf("ground truth: %d queries with a revisit, median roll difference %.1f deg -> %s\n",
              gt.positives(), median_roll, args.gt.c_str());
  if (!args.bag.empty()) std::printf("bag: %s\n", args.bag.c_str());
  if (!args.images.empty()) std::printf("images: %s\n", args.images.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bowg_generate_pipe_sequence: %s\n", e.what());
    return 1;
  }
}
