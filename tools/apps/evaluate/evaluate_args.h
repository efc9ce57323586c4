// bowg_evaluate's command line: the options and their parser.
#pragma once

#include <string>
#include <vector>

namespace bowg {
namespace evaluate_app {

extern const char* const kUsage;

struct Args {
  std::string bag, image_topic = "/camera/image_raw", info_topic = "/camera/camera_info";
  std::string images, vocabulary, config, gt, output = "bowg_evaluation", sweep = "rerun";
  std::string odometry;
  std::string odometry_poses;
  std::string odometer_topic;     ///< --odometer-topic: metres driven in the bag
  std::string odom_topic;         ///< --odom-topic: nav_msgs/Odometry positions in the bag
  std::string missions;           ///< --missions: the frames where each mission starts
  std::vector<std::string> maps;  ///< --map (repeatable): earlier missions to start from
  std::string save_map;           ///< --save-map: the last row's detector after the run
  long skip_frames = 0;           ///< --skip-frames: input frames left out first
  std::string mission_name;       ///< --mission-name: the run's mission ("" = none given)
  long long mission_id = -1;      ///< --mission-id (-1 = the next free one)
  std::string intrinsics;         ///< --intrinsics: fx,fy,cx,cy of folder images
  std::string dump_candidates;
  double rate = 1.0;
  long max_frames = 0;
  int jobs = 0;
  bool ablation = false, quiet = false;
  std::vector<std::string> rows{"bow", "word_groups", "temporal", "distribution"};
  std::vector<double> thresholds;
};

/// Throws std::invalid_argument naming the flag (see kUsage); exits 0 on --help.
Args parseArgs(int argc, char** argv);

}  // namespace evaluate_app
}  // namespace bowg
