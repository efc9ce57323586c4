// bowg_pose_graph end to end on a synthetic two-lap circuit: drifting
// odometry, loops at the revisited places; the error with the loops must
// drop well below the odometry's, and bad input must name the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "shell_command.h"
#include "synthetic_circuit.h"

namespace bowg {
namespace {

using tool_test::readAll;
using tool_test::run;
using tool_test::Pose2;

const std::string kOut = std::string(BOWG_TEST_OUTPUT_DIR) + "/pose_graph_cli";

void writePoses(const std::string& path, const std::vector<Pose2>& poses) {
  std::ofstream f(path);
  f << "frame,stamp,x,y,z,qx,qy,qz,qw\n";
  for (std::size_t i = 0; i < poses.size(); ++i) {
    f << i << "," << 100 + 0.1 * i << "," << poses[i].x << "," << poses[i].y << ",0,0,0,"
      << std::sin(poses[i].yaw / 2) << "," << std::cos(poses[i].yaw / 2) << "\n";
  }
}

double number(const std::string& text, const std::string& after) {
  const std::size_t at = text.find(after);
  if (at == std::string::npos) return NAN;
  return std::atof(text.c_str() + at + after.size());
}

TEST(PoseGraphCli, LoopsBringTheTrajectoryBackToTheTruth) {
  run("rm -rf " + kOut + " && mkdir -p " + kOut);
  std::vector<Pose2> truth, odometry;
  tool_test::twoLapCircuit(&truth, &odometry);
  ASSERT_EQ(truth.size(), 600u);
  writePoses(kOut + "/poses.csv", truth);
  writePoses(kOut + "/odometry.csv", odometry);
  // Every 10th frame of lap 2 revisits frame - 300 of lap 1.
  {
    std::ofstream f(kOut + "/detections.csv");
    f << "query,match,score\n";
    for (int q = 310; q < 600; q += 10) f << q << "," << q - 300 << ",1.0\n";
  }
  const std::string log = kOut + "/run.log";
  ASSERT_EQ(run(std::string(BOWG_POSE_GRAPH_BIN) + " --truth " + kOut + "/poses.csv --odometry " +
                    kOut + "/odometry.csv --loops " + kOut + "/detections.csv --output " + kOut +
                    "/out",
                log),
            0)
      << readAll(log);
  const std::string out = readAll(log);
  const double before = number(out, "odometry only       : position RMSE ");
  const double after = number(out, "pose graph + loops  : position RMSE ");
  std::printf("%s", out.c_str());
  ASSERT_TRUE(std::isfinite(before) && std::isfinite(after)) << out;
  EXPECT_GT(before, 1.0);          // 3 % and 0.4 deg/m over 120 m: metres off (4.2 m)
  EXPECT_LT(after, before / 3.0);  // the loops pull lap 2 onto lap 1, lap 1 onto the truth
  EXPECT_NE(out.find("600 frames, 119.8 m driven, 29 loops"), std::string::npos) << out;
  EXPECT_EQ(readAll(kOut + "/out/summary.txt"), out.substr(0, out.find("outputs in")));
  const cv::Mat png = cv::imread(kOut + "/out/trajectories.png");
  EXPECT_EQ(png.cols, 900);
  const std::string csv = readAll(kOut + "/out/trajectories.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 601);
}

// The two laps as two surveys: lap 2's odometry restarted in a frame of its
// own (turned 70 deg, moved by (5, -3)). Placed by its loops into lap 1 and
// optimised, it ends where it would have with the frames shared: the result
// does not depend on where the second frame lies. A survey with no loop into
// an earlier one cannot be placed and is refused by name.
TEST(PoseGraphCli, ASecondSurveyInItsOwnFrameIsPlacedByItsLoops) {
  run("mkdir -p " + kOut);
  std::vector<Pose2> truth, odometry;
  tool_test::twoLapCircuit(&truth, &odometry);
  std::vector<Pose2> moved = odometry;
  const double yaw = 70 * 3.14159265358979323846 / 180, c = std::cos(yaw), s = std::sin(yaw);
  for (std::size_t i = 300; i < moved.size(); ++i) {
    const Pose2& o = odometry[i];
    moved[i] = {c * o.x - s * o.y + 5, s * o.x + c * o.y - 3, o.yaw + yaw};
  }
  writePoses(kOut + "/m_poses.csv", truth);
  writePoses(kOut + "/m_odometry.csv", odometry);
  writePoses(kOut + "/m_moved.csv", moved);
  {
    std::ofstream f(kOut + "/m_detections.csv");
    f << "query,match,score\n";
    for (int q = 310; q < 600; q += 10) f << q << "," << q - 300 << ",1.0\n";
    std::ofstream m(kOut + "/missions.csv");
    m << "0,1,lap one\n300,2,lap two\n";
  }
  const std::string bin = std::string(BOWG_POSE_GRAPH_BIN) + " --truth " + kOut +
                          "/m_poses.csv --loops " + kOut + "/m_detections.csv --missions " + kOut +
                          "/missions.csv --odometry " + kOut;
  ASSERT_EQ(run(bin + "/m_moved.csv", kOut + "/moved.log"), 0) << readAll(kOut + "/moved.log");
  ASSERT_EQ(run(bin + "/m_odometry.csv", kOut + "/shared.log"), 0) << readAll(kOut + "/shared.log");
  const std::string moved_out = readAll(kOut + "/moved.log");
  const std::string shared_out = readAll(kOut + "/shared.log");
  std::printf("%s", moved_out.c_str());
  EXPECT_NE(moved_out.find("mission 2 'lap two': 300 frames, 29 loops into earlier missions"),
            std::string::npos)
      << moved_out;
  const double own = number(moved_out, "in its own odometry frame: RMSE ");
  const double placed = number(moved_out, "placed by its loops      : RMSE ");
  const double after = number(moved_out, "pose graph + loops       : RMSE ");
  const double after_shared = number(shared_out, "pose graph + loops       : RMSE ");
  ASSERT_TRUE(std::isfinite(own) && std::isfinite(placed) && std::isfinite(after)) << moved_out;
  EXPECT_GT(own, 5.0);  // metres away in a frame of its own
  EXPECT_LT(placed, 0.5 * own);
  // Each lap is one pass with no loop of its own: lap 2 lands on lap 1 as
  // lap 1's odometry drew it (its drift stays, nothing measures it), and
  // the graph keeps it there.
  EXPECT_LE(after, placed + 0.01);
  EXPECT_NEAR(after, after_shared, 0.01);
  {
    std::ofstream f(kOut + "/m_lap1_only.csv");
    f << "query,match,score\n";
    for (int q = 100; q < 300; q += 10) f << q << "," << q - 50 << ",1.0\n";
  }
  const std::string log = kOut + "/no_cross.log";
  EXPECT_EQ(run(std::string(BOWG_POSE_GRAPH_BIN) + " --truth " + kOut + "/m_poses.csv --loops " +
                    kOut + "/m_lap1_only.csv --missions " + kOut + "/missions.csv --odometry " +
                    kOut + "/m_moved.csv",
                log),
            1);
  EXPECT_NE(readAll(log).find("mission 2 'lap two' has no loop into an earlier mission"),
            std::string::npos)
      << readAll(log);
}

// Out 2 m and back along x, facing +x; the last frame stands 4 cm ahead of
// the first. A metric loop that says so (optical z forward: the match camera
// 4 cm behind the query, X_Q = X_M + (0, 0, -0.04)) is reported with no
// error; the same-place edge's error is the 4 cm.
TEST(PoseGraphCli, MetricLoopsAreMeasuredAgainstTheTruth) {
  run("mkdir -p " + kOut);
  writePoses(kOut + "/line.csv", {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1.02, 0, 0}, {0.04, 0, 0}});
  writePoses(kOut + "/line_odometry.csv",
             {{0, 0, 0}, {1.03, 0, 0}, {2.06, 0, 0}, {1.05, 0, 0}, {0.05, 0, 0}});
  {
    std::ofstream d(kOut + "/line_loops.csv");
    d << "query,match,score\n4,0,1.0\n";
    std::ofstream p(kOut + "/line_poses.csv");
    p << "query,match,metric_status,r00,r01,r02,r10,r11,r12,r20,r21,r22,tx,ty,tz,cxx,cxy,cxz,"
         "cyy,cyz,czz\n"
         "4,0,estimated,1,0,0,0,1,0,0,0,1,0,0,-0.04,1e-6,0,0,1e-6,0,1e-6\n";
  }
  const std::string log = kOut + "/line.log";
  ASSERT_EQ(run(std::string(BOWG_POSE_GRAPH_BIN) + " --truth " + kOut + "/line.csv --odometry " +
                    kOut + "/line_odometry.csv --loops " + kOut + "/line_loops.csv --loop-poses " +
                    kOut + "/line_poses.csv",
                log),
            0)
      << readAll(log);
  const std::string out = readAll(log);
  EXPECT_NE(out.find("metric loops        : 1 of 1"), std::string::npos) << out;
  EXPECT_NEAR(number(out, "position error     : median "), 0.0, 1e-3) << out;
  EXPECT_NEAR(number(out, "the same-place edge's: median "), 0.04, 1e-3) << out;
  EXPECT_NE(out.find("inside the 95 % covariance ellipsoid: 100 %"), std::string::npos) << out;
  // The metric loop pulls the last frame to 4 cm ahead of the first.
  const double after = number(out, "pose graph + loops  : position RMSE ");
  const double before = number(out, "odometry only       : position RMSE ");
  EXPECT_LT(after, before) << out;
}

TEST(PoseGraphCli, BadInputNamesTheFile) {
  run("mkdir -p " + kOut);
  writePoses(kOut + "/short.csv", {{0, 0, 0}, {1, 0, 0}});
  {
    std::ofstream f(kOut + "/far.csv");
    f << "query,match,score\n5,0,1.0\n";
  }
  const std::string log = kOut + "/bad.log";
  const std::string bin = BOWG_POSE_GRAPH_BIN;
  EXPECT_EQ(run(bin + " --truth " + kOut + "/short.csv --odometry " + kOut + "/short.csv --loops " +
                    kOut + "/far.csv",
                log),
            1);
  EXPECT_NE(readAll(log).find(kOut + "/far.csv: loop 5 -> 0 names frame 5, which " + kOut +
                              "/short.csv does not hold"),
            std::string::npos)
      << readAll(log);
  EXPECT_EQ(run(bin + " --truth " + kOut + "/short.csv --odometry " + kOut + "/missing.csv --loops " +
                    kOut + "/far.csv",
                log),
            1);
  EXPECT_NE(readAll(log).find("cannot open the trajectory file '" + kOut +
                              "/missing.csv': No such file or directory"),
            std::string::npos);
  {
    std::ofstream f(kOut + "/bad_poses.csv");
    f << "query,match\n";
  }
  EXPECT_EQ(run(bin + " --truth " + kOut + "/short.csv --odometry " + kOut + "/short.csv --loops " +
                    kOut + "/far.csv --loop-poses " + kOut + "/bad_poses.csv",
                log),
            1);
  EXPECT_NE(readAll(log).find(kOut + "/bad_poses.csv:1: expected the header"), std::string::npos)
      << readAll(log);
  EXPECT_EQ(run(bin + " --truth x", log), 2);
  EXPECT_NE(readAll(log).find("--truth, --odometry and --loops are required"), std::string::npos);
  EXPECT_EQ(run(bin + " --truth a --odometry b --loops c --loop-sigma -1", log), 2);
  EXPECT_NE(readAll(log).find("loop_position_sigma"), std::string::npos) << readAll(log);
}

}  // namespace
}  // namespace bowg
