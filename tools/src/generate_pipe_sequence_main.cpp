// bowg_generate_pipe_sequence: renders the in-pipe sequence (see
// docs/pipe_sequence.md) into a rosbag and/or a PNG folder, plus the loop
// ground truth computed from the poses.
//
//   rosrun bowg_ros bowg_generate_pipe_sequence --bag pipe.bag [--images DIR]
//       [--gt pipe_gt.txt] [--laps 1] [--frames N] [--seed 1] [--width 640]
//       [--height 480] [--fx 320] [--roll-amplitude 60] [--marks-per-metre 1]
//       [--grain-repeat 0.5]
//       [--speed 0.2] [--rate 10] [--gt-distance 0.15] [--gt-heading 30]
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
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>

#include "bowg/atomic_file.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/wall_texture.h"

namespace {

using namespace bowg;
using namespace bowg::pipe_sim;

const char* kUsage =
    "usage: bowg_generate_pipe_sequence (--bag FILE | --images DIR) [options]\n"
    "  --bag FILE             write a rosbag: /camera/image_raw (mono8), /camera/camera_info,\n"
    "                         /ground_truth/pose (geometry_msgs/PoseStamped, frame map)\n"
    "  --images DIR           write frame_000000.png ... (and poses.csv) into DIR\n"
    "  --gt FILE              ground-truth loops (default: <bag>_gt.txt or DIR/ground_truth.txt)\n"
    "  --laps N               laps of the route (48 m of pipe each) [1]\n"
    "  --frames N             stop after N frames (0 = whole route) [0]\n"
    "  --seed N               texture, roll, exposure and noise seed [1]\n"
    "  --width W --height H   image size [640 480]\n"
    "  --fx F                 focal length in px (fy = fx, principal point at the centre) [W/2]\n"
    "  --roll-amplitude DEG   roll about the pipe axis in [-DEG, DEG] [60]\n"
    "  --marks-per-metre X    unique wall marks per metre (texture repetitiveness) [1]\n"
    "  --grain-repeat G       fraction of the wall grain repeated in every section, in [0, 1]\n"
    "                         (1 = pixel-identical sections, 0 = no shared grain) [0.5]\n"
    "  --speed MPS --rate HZ  driving speed and frame rate [0.2 10]\n"
    "  --gt-distance M --gt-heading DEG --gt-exclude M\n"
    "                         ground-truth tolerances [0.15 30 3]\n"
    "  --compression C        bag compression: none, lz4 or bz2 (noisy images hardly\n"
    "                         compress) [none]\n";

struct Args {
  std::string bag, images, gt, compression = "none";
  SequenceOptions sequence;
  WallTextureOptions texture;
  CameraModel camera;
  eval::GroundTruthOptions gt_options;
};

double toNumber(const std::string& flag, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v)) {
    throw std::invalid_argument(flag + ": '" + value + "' is not a number");
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
    if (i + 1 >= argc) throw std::invalid_argument(flag + ": missing value (see --help)");
    const std::string v = argv[++i];
    if (flag == "--bag") a.bag = v;
    else if (flag == "--images") a.images = v;
    else if (flag == "--gt") a.gt = v;
    else if (flag == "--compression") a.compression = v;
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

int run(int argc, char** argv) {
  const Args args = parseArgs(argc, argv);
  const PipeNetwork network = PipeNetwork::figureEight(args.sequence.network_width_m,
                                                       args.sequence.network_height_m);
  const Route route(network, defaultRouteNodes(args.sequence.laps), args.sequence.bend_radius_m);
  const std::vector<FrameState> frames = planSequence(route, args.sequence);
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
  poses_csv << "frame,stamp,x,y,z,qx,qy,qz,qw,roll_deg,exposure,distance\n";
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
      sensor_msgs::Image msg;
      msg.header.seq = f.index;
      msg.header.stamp = stamp;
      msg.header.frame_id = info.header.frame_id;
      msg.height = image.rows;
      msg.width = image.cols;
      msg.encoding = sensor_msgs::image_encodings::MONO8;
      msg.is_bigendian = 0;
      msg.step = image.cols;
      msg.data.assign(image.data, image.data + image.total());
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
      bag.write("/camera/image_raw", stamp, msg);
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
              << f.distance << "\n";
    eval::TravelPose tp;
    tp.x = f.pose.position[0];
    tp.y = f.pose.position[1];
    tp.z = f.pose.position[2];
    tp.hx = f.tangent[0];
    tp.hy = f.tangent[1];
    tp.hz = f.tangent[2];
    tp.distance = f.distance;
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
  std::sort(roll_differences.begin(), roll_differences.end());
  const double median_roll =
      roll_differences.empty() ? 0 : roll_differences[roll_differences.size() / 2];
  std::ostringstream header;
  header << "bowg_ros pipe sequence ground truth (docs/pipe_sequence.md)\n"
         << "query: matches; 0-based index of the image messages (frames)\n"
         << "frames " << frames.size() << ", seed " << args.sequence.seed << ", laps "
         << args.sequence.laps << ", marks_per_metre " << args.texture.marks_per_metre
         << ", grain_repeat " << args.texture.grain_repeat
         << ", roll_amplitude_deg " << args.sequence.roll_amplitude_deg << "\n"
         << "tolerances: distance < " << args.gt_options.max_distance_m << " m, heading < "
         << args.gt_options.max_heading_deg << " deg, excluding the last "
         << args.gt_options.exclude_recent_m << " m driven\n"
         << "queries with a revisit " << gt.positives() << ", median roll difference "
         << median_roll << " deg";
  eval::writeGroundTruth(args.gt, gt, header.str());

  std::printf("frames: %zu (%.1f m driven)\n", frames.size(), frames.back().distance);
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
