// scripts/pose_graph_demo.sh on a short rendered network (473 frames, two
// passes through the T-junctions, drifting odometry, the detector's loops
// with config/pipe.yaml): the trajectory error with the loops, at the
// match's place or metric, must be lower than the odometry's, and the metric
// translations closer to the truth than "the same place". ~60 s.
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
  // Two graphs: every loop at the match's place, then the metric loops.
  const std::string graph = "pose graph + loops  : position RMSE ";
  const double same_place = number(text, graph);
  const std::string metric_run = text.substr(text.find("metric loops where"));
  const double metric = number(metric_run, graph);
  ASSERT_TRUE(std::isfinite(before) && std::isfinite(same_place) && std::isfinite(metric)) << text;
  EXPECT_GT(before, 0.1);  // the odometry drifts (0.26 m RMSE on this run)
  EXPECT_LT(same_place, 0.75 * before);
  EXPECT_LT(metric, 0.75 * before);
  // The detector measured some loops' translation (intrinsics and odometry
  // given), and closer to the truth than "the same place" says.
  EXPECT_GT(number(metric_run, "metric loops        : "), 0) << text;
  EXPECT_LT(number(metric_run, "position error     : median "),
            number(metric_run, "the same-place edge's: median "))
      << text;
  EXPECT_FALSE(readAll(out + "/graph/trajectories.png").empty());
  RecordProperty("odometry_rmse_m", std::to_string(before));
  RecordProperty("pose_graph_rmse_m", std::to_string(same_place));
  RecordProperty("pose_graph_metric_rmse_m", std::to_string(metric));
}

}  // namespace
}  // namespace bowg
