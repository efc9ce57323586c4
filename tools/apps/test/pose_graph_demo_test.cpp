// scripts/pose_graph_demo.sh on a short rendered network (473 frames, two
// passes through the T-junctions, drifting odometry, the detector's loops
// with config/pipe.yaml): the trajectory error with the loops must be lower
// than the odometry's. ~40 s.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "shell_command.h"

namespace bowg {
namespace {

using tool_test::readAll;
using tool_test::run;

double number(const std::string& text, const std::string& after) {
  const std::size_t at = text.find(after);
  return at == std::string::npos ? NAN : std::atof(text.c_str() + at + after.size());
}

TEST(PoseGraphDemo, LoopsFromTheDetectorLowerTheTrajectoryError) {
  const std::string out = std::string(BOWG_TEST_OUTPUT_DIR) + "/pose_graph_demo";
  const std::string log = out + ".log";
  ASSERT_EQ(run("BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_TOOLS_DIR=" BOWG_TOOLS_BIN_DIR
                " BOWG_POSE_GRAPH_DIR=" + out +
                    " BOWG_POSE_GRAPH_ARGS='--seed 31 --rate 2 --marks-per-metre 8' "
                    "bash " BOWG_REPO_DIR "/scripts/pose_graph_demo.sh",
                log),
            0)
      << readAll(log);
  const std::string text = readAll(log);
  std::printf("%s", text.c_str());
  const double before = number(text, "odometry only       : position RMSE ");
  const double after = number(text, "pose graph + loops  : position RMSE ");
  ASSERT_TRUE(std::isfinite(before) && std::isfinite(after)) << text;
  EXPECT_GT(before, 0.1);  // the odometry drifts (0.26 m RMSE on this run)
  EXPECT_LT(after, 0.75 * before);
  EXPECT_FALSE(readAll(out + "/graph/trajectories.png").empty());
  RecordProperty("odometry_rmse_m", std::to_string(before));
  RecordProperty("pose_graph_rmse_m", std::to_string(after));
}

}  // namespace
}  // namespace bowg
