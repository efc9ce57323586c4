// bowg_evaluate's command line (evaluate_args.h).
#include "evaluate_args.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bowg/detection/detection_options.h"
#include "bowg_evaluation/command_line.h"

namespace bowg {
namespace evaluate_app {

const char* const kUsage =
    "usage: bowg_evaluate (--bag FILE | --images DIR) --vocabulary FILE [options]\n"
    "Input:\n"
    "  --bag FILE                 rosbag with the images\n"
    "  --image-topic T            sensor_msgs/Image or CompressedImage topic\n"
    "                             [/camera/image_raw]\n"
    "  --camera-info-topic T      sensor_msgs/CameraInfo topic, 'none' to ignore "
    "[/camera/camera_info]\n"
    "  --images DIR               image folder (png/jpg/jpeg/pgm/bmp, sorted by file name)\n"
    "  --rate HZ                  stamps of folder images: frame n at n / HZ s [1]\n"
    "  --max-frames N             use the first N images only [all]\n"
    "  --intrinsics FILE          camera of folder images (CSV 'fx,fy,cx,cy', one row; the\n"
    "                             generator's intrinsics.csv): loops get their relative pose\n"
    "  --odometry FILE            metres driven per frame (CSV with 'frame' and 'odometer' or\n"
    "                             'distance' columns, e.g. the generator's poses.csv, or a pose\n"
    "                             file's x,y,z: its path length, e.g. the drifting\n"
    "                             odometry.csv): the windows in metres (recent_exclusion_m) and\n"
    "                             with --intrinsics the loops' metric translation\n"
    "  --odometry-poses FILE      the robot's dead-reckoned position per frame (CSV with 'frame',\n"
    "                             'x', 'y', 'z', e.g. the generator's drifting odometry.csv):\n"
    "                             with --odometry, the odometry gate (odometry_gate_m)\n"
    "  --odometer-topic T         with --bag: odometer readings (metres driven, a cable counter)\n"
    "                             as the nodelet takes them (instead of --odometry):\n"
    "                             std_msgs/Float64 (the generator's /odometer), each image gets\n"
    "                             the path of the readings before it in the bag; or\n"
    "                             bowg_ros/OdometerStamped (/odometer_stamped), the path of the\n"
    "                             readings stamped at or before the image\n"
    "  --odom-topic T             with --bag: odometry positions (nav_msgs/Odometry, the\n"
    "                             generator's /odom) as the nodelet takes them (instead of\n"
    "                             --odometry and --odometry-poses): each image gets the\n"
    "                             position stamped at or before it and the path length so far\n"
    "  --missions FILE            the frames where each mission starts (CSV lines\n"
    "                             first_frame,mission_id,name; the generator's missions.csv):\n"
    "                             each mission is started as the nodelet's ~mission_name starts\n"
    "                             one, and the summary scores the loops across missions\n"
    "  --mission-name NAME        the run's mission (as the nodelet's ~mission_name), e.g.\n"
    "                             the survey date [with --map: the input's file name]\n"
    "  --mission-id N             its id (as ~mission_id) [the next free one]\n"
    "  --skip-frames N            leave out the input's first N frames (after --max-frames;\n"
    "                             the ground truth, odometry and missions still index the\n"
    "                             input) [0]\n"
    "Re-inspection (docs/evaluation.md, \"Reference maps\"):\n"
    "  --map FILE                 an earlier mission's saved database (the nodelet's, a\n"
    "                             bowg_merge_databases output or --save-map), repeatable:\n"
    "                             every run starts on them as the nodelet starts on\n"
    "                             ~reference_maps; their keyframes are entries 0..M-1, the\n"
    "                             input's frames follow (the ground truth is moved to match)\n"
    "  --save-map FILE            after the run, save the last row's detector (atomic): a\n"
    "                             map for a later --map or for the nodelet\n"
    "Engine:\n"
    "  --vocabulary FILE          any format bowg::loadVocabulary reads (required)\n"
    "  --config FILE              parameter file, e.g. config/pipe.yaml [engine defaults]\n"
    "Evaluation:\n"
    "  --gt FILE                  ground truth 'query: match,...' (0-based frame indices)\n"
    "  --output DIR               where CSVs, the PR plot and summary.txt go [bowg_evaluation]\n"
    "  --ablation                 run bow, word_groups, temporal, distribution side by side\n"
    "  --rows A,B,...             ablation rows to run instead (implies --ablation): bow,\n"
    "                             word_groups, temporal, distribution (each with the\n"
    "                             configuration's extensions), paper (the paper's method as\n"
    "                             written), paper_bow (its pipeline with pure bag of words:\n"
    "                             DBoW2 + DLoopDetector), configured (the configuration),\n"
    "                             without_floor, without_normaliser_distance,\n"
    "                             without_alignment, without_missed_queries,\n"
    "                             without_hypotheses, without_min_step,\n"
    "                             without_linked_places, without_odometry_gate (every\n"
    "                             gate), without_heading_gate, without_loop_anchor,\n"
    "                             without_anchored_chain,\n"
    "                             without_place_index, without_ransac_bound,\n"
    "                             without_native_ransac, without_reranking,\n"
    "                             without_verified_chain\n"
    "                             (the configuration with one extension switched off)\n"
    "  --sweep rerun|score        PR curve: re-run the detector per threshold (exact, slower)\n"
    "                             or sweep the final score of one run at the lowest threshold\n"
    "                             [rerun]\n"
    "  --thresholds LO:STEP:HI|A,B,C   min_score values of the sweep [0.2:0.2:2]; the\n"
    "                             configured min_score is always one of them\n"
    "  --jobs N                   threads for the re-runs of the sweep (0 = one per core) [0];\n"
    "                             the timing runs at the configured threshold run alone\n"
    "  --quiet                    no progress bar\n"
    "Diagnosis:\n"
    "  --dump-candidates FILE     with --gt: one run of the configured detector (every score on,\n"
    "                             minimum normalisers 0) writing, per query with a revisit, the\n"
    "                             rank of the best true match under eta_w, eta_g, eta_d, eta_sim\n"
    "                             and eta, the normalisers and the feature count (CSV); prints\n"
    "                             the top-1 rates and median ranks, then stops\n";

namespace {

std::vector<double> parseThresholds(const std::string& v) {
  std::vector<double> out;
  if (v.find(':') != std::string::npos) {
    std::istringstream in(v);
    std::string a, b, c;
    if (!std::getline(in, a, ':') || !std::getline(in, b, ':') || !std::getline(in, c, ':')) {
      throw std::invalid_argument("--thresholds: expected LO:STEP:HI, got " + v);
    }
    const double lo = eval::numberArgument("--thresholds", a),
                 step = eval::numberArgument("--thresholds", b),
                 hi = eval::numberArgument("--thresholds", c);
    if (!(step > 0) || hi < lo || (hi - lo) / step > 1000) {
      throw std::invalid_argument("--thresholds: need STEP > 0, HI >= LO, at most 1000 values");
    }
    for (int i = 0; lo + i * step <= hi + 1e-9; ++i) out.push_back(lo + i * step);
  } else {
    std::istringstream in(v);
    std::string item;
    while (std::getline(in, item, ',')) out.push_back(eval::numberArgument("--thresholds", item));
  }
  for (double t : out) {
    if (t < 0) throw std::invalid_argument("--thresholds: min_score values must be >= 0");
  }
  if (out.empty()) throw std::invalid_argument("--thresholds: no value");
  std::sort(out.begin(), out.end(), std::greater<double>());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<std::string> splitList(const std::string& v) {
  std::vector<std::string> out;
  std::istringstream in(v);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// What one flag cannot say alone: the input and the engine's.
void checkInput(const Args& a) {
  if (a.bag.empty() == a.images.empty()) {
    throw std::invalid_argument("give exactly one of --bag FILE and --images DIR (see --help)");
  }
  if (a.vocabulary.empty()) throw std::invalid_argument("--vocabulary FILE is required");
  if (a.sweep != "rerun" && a.sweep != "score") {
    throw std::invalid_argument("--sweep must be rerun or score, not " + a.sweep);
  }
  if (!(a.rate > 0)) throw std::invalid_argument("--rate must be > 0");
  if (!a.intrinsics.empty() && a.images.empty()) {
    throw std::invalid_argument("--intrinsics is for --images (a bag's camera_info gives them)");
  }
  if (a.max_frames < 0) throw std::invalid_argument("--max-frames must be >= 0");
  if (!a.odometer_topic.empty() && a.bag.empty()) {
    throw std::invalid_argument("--odometer-topic is for --bag (an image folder takes --odometry)");
  }
  if (!a.odometer_topic.empty() && !a.odometry.empty()) {
    throw std::invalid_argument("give one of --odometer-topic and --odometry, not both");
  }
  if (!a.odom_topic.empty() && a.bag.empty()) {
    throw std::invalid_argument(
        "--odom-topic is for --bag (an image folder takes --odometry-poses)");
  }
  if (!a.odom_topic.empty() && (!a.odometry.empty() || !a.odometry_poses.empty())) {
    throw std::invalid_argument(
        "give --odom-topic or --odometry/--odometry-poses, not both: they measure the same path");
  }
}

// The missions, maps and frames left out.
void checkMissions(const Args& a) {
  if (a.skip_frames < 0) throw std::invalid_argument("--skip-frames must be >= 0");
  if (a.max_frames > 0 && a.skip_frames >= a.max_frames) {
    throw std::invalid_argument("--skip-frames must be below --max-frames");
  }
  if (a.mission_id < -1 || a.mission_id > 4294967295LL) {
    throw std::invalid_argument("--mission-id must be in [0, 2^32) (or -1: the next free one)");
  }
  if (!a.missions.empty() && (!a.mission_name.empty() || a.mission_id != -1)) {
    throw std::invalid_argument("give --missions FILE or --mission-name/--mission-id, not both");
  }
  if (a.mission_id != -1 && a.mission_name.empty()) {
    throw std::invalid_argument("--mission-id needs --mission-name");
  }
  if (!a.dump_candidates.empty() && (!a.maps.empty() || !a.save_map.empty())) {
    throw std::invalid_argument("--dump-candidates does not take --map or --save-map");
  }
}

void checkArgs(const Args& a) {
  checkInput(a);
  checkMissions(a);
}

}  // namespace

Args parseArgs(int argc, char** argv) {
  Args a;
  a.thresholds = parseThresholds("0.2:0.2:2");
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "-h" || flag == "--help") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (flag == "--ablation") {
      a.ablation = true;
      continue;
    }
    if (flag == "--quiet") {
      a.quiet = true;
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(flag + ": missing value (see --help)");
    const std::string v = argv[++i];
    if (flag == "--bag")
      a.bag = v;
    else if (flag == "--image-topic")
      a.image_topic = v;
    else if (flag == "--camera-info-topic")
      a.info_topic = v;
    else if (flag == "--images")
      a.images = v;
    else if (flag == "--rate")
      a.rate = eval::numberArgument(flag, v);
    else if (flag == "--max-frames")
      a.max_frames = static_cast<long>(eval::numberArgument(flag, v));
    else if (flag == "--vocabulary")
      a.vocabulary = v;
    else if (flag == "--config")
      a.config = v;
    else if (flag == "--gt")
      a.gt = v;
    else if (flag == "--output")
      a.output = v;
    else if (flag == "--sweep")
      a.sweep = v;
    else if (flag == "--thresholds")
      a.thresholds = parseThresholds(v);
    else if (flag == "--dump-candidates")
      a.dump_candidates = v;
    else if (flag == "--odometry")
      a.odometry = v;
    else if (flag == "--odometry-poses")
      a.odometry_poses = v;
    else if (flag == "--missions")
      a.missions = v;
    else if (flag == "--map")
      a.maps.push_back(v);
    else if (flag == "--save-map")
      a.save_map = v;
    else if (flag == "--skip-frames")
      a.skip_frames = static_cast<long>(eval::numberArgument(flag, v));
    else if (flag == "--mission-name")
      a.mission_name = v;
    else if (flag == "--mission-id") {
      const double id = eval::numberArgument(flag, v);
      if (id != std::floor(id)) throw std::invalid_argument("--mission-id must be an integer");
      a.mission_id = static_cast<long long>(id);
    } else if (flag == "--odometer-topic")
      a.odometer_topic = v;
    else if (flag == "--odom-topic")
      a.odom_topic = v;
    else if (flag == "--intrinsics")
      a.intrinsics = v;
    else if (flag == "--rows") {
      a.rows = splitList(v);
      if (a.rows.empty()) throw std::invalid_argument("--rows needs at least one row");
      for (const std::string& row : a.rows)
        LoopDetectorOptions::ablation(row, LoopDetectorOptions());
      a.ablation = true;
    } else if (flag == "--jobs") {
      const double j = eval::numberArgument(flag, v);
      if (j < 0 || j > 256 || j != static_cast<int>(j)) {
        throw std::invalid_argument("--jobs must be an integer in [0, 256]");
      }
      a.jobs = static_cast<int>(j);
    } else
      throw std::invalid_argument("unknown option " + flag + " (see --help)");
  }
  checkArgs(a);
  return a;
}
}  // namespace evaluate_app
}  // namespace bowg
