#include "pose_graph_args.h"

#include <stdexcept>

#include "bowg_evaluation/command_line.h"

namespace bowg {
namespace pose_graph_app {

const char* const kUsage =
    "usage: bowg_pose_graph --truth POSES.csv --odometry ODOMETRY.csv --loops DETECTIONS.csv\n"
    "                       [--loop-poses LOOP_POSES.csv] [--output DIR] [--loop-sigma M]\n"
    "                       [--odometry-sigma FRACTION] [--robust SIGMAS] [--missions FILE]\n"
    "\n"
    "The pose-graph example: one node per frame of the odometry, odometry edges between\n"
    "consecutive frames, one loop edge per detection (the query at the match's place,\n"
    "within --loop-sigma), optimised with Ceres. Prints the position error against the\n"
    "truth without and with the loops.\n"
    "  --truth FILE        true body poses per frame (frame,x,y,z,qx,qy,qz,qw; the\n"
    "                      generator's poses.csv)\n"
    "  --odometry FILE     odometry poses per frame, same columns (the generator's\n"
    "                      odometry.csv); the same frames as --truth\n"
    "  --loops FILE        query,match,score per loop, frame indices (bowg_evaluate's\n"
    "                      detections_<row>.csv)\n"
    "  --loop-poses FILE   the loops' relative poses (bowg_evaluate's loop_poses_<row>.csv):\n"
    "                      a loop with a metric translation puts the query where it says,\n"
    "                      with its covariance (camera at the body's origin looking along\n"
    "                      x, the generator's); also prints that translation's error\n"
    "  --output DIR        writes trajectories.csv, summary.txt and trajectories.png\n"
    "  --loop-sigma M      sigma of the query's position at the match's place [0.15]\n"
    "  --odometry-sigma F  sigma of an odometry step's position, fraction of its length [0.05]\n"
    "  --robust SIGMAS     Cauchy loss scale on the loops, in sigmas; 0 = none [3]\n"
    "  --missions FILE     where each survey starts (first_frame,mission_id,name; the\n"
    "                      generator's missions.csv): each survey's odometry is a frame of\n"
    "                      its own, placed by its loops into the earlier ones; prints each\n"
    "                      later survey's error in its own frame, placed and optimised\n";

Args parseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(flag + " needs a value");
      return argv[++i];
    };
    if (flag == "--truth") {
      a.truth = value();
    } else if (flag == "--odometry") {
      a.odometry = value();
    } else if (flag == "--loops") {
      a.loops = value();
    } else if (flag == "--loop-poses") {
      a.loop_poses = value();
    } else if (flag == "--output") {
      a.output = value();
    } else if (flag == "--missions") {
      a.missions = value();
    } else if (flag == "--loop-sigma") {
      a.graph.loop_position_sigma = eval::numberArgument(flag, value());
    } else if (flag == "--odometry-sigma") {
      a.graph.odometry_position_fraction = eval::numberArgument(flag, value());
    } else if (flag == "--robust") {
      a.graph.loop_robust_sigmas = eval::numberArgument(flag, value());
    } else {
      throw std::invalid_argument("unknown option '" + flag + "'");
    }
  }
  if (a.truth.empty() || a.odometry.empty() || a.loops.empty()) {
    throw std::invalid_argument("--truth, --odometry and --loops are required");
  }
  a.graph.validate();
  return a;
}

}  // namespace pose_graph_app
}  // namespace bowg
