// End-to-end tests of bowg_generate_pipe_sequence's drifting odometry on
// tiny sequences: odometry.csv has poses.csv's frames and stamps and starts
// at the first true pose, equals poses.csv when every odometry noise is 0,
// the bag carries the same poses on /odom, the summary reports the drift,
// and bad odometry options are refused naming the flag. The re-inspection
// (--again): missions.csv, frames, stamps and the odometer continue, the
// second mission's odometry restarts, its queries match the first mission's
// frames, the first mission is the run without --again, bad values refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/Float64.h>

#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/odometry_file.h"
#include "shell_command.h"

namespace bowg {
namespace {

using tool_test::readAll;
using tool_test::readCsv;
using tool_test::run;
using tool_test::Table;

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/generate_pipe_sequence_test";
const std::string kGenerator = BOWG_GENERATOR_BIN;
// 60 frames 10 cm apart: along the first pipe and round the first bend.
const std::string kSequence = " --frames 60 --speed 1.0 --width 64 --height 48";
const std::string kNoOdometryNoise =
    " --odometry-slip 0 --odometry-slip-noise 0 --odometry-heading-drift 0"
    " --odometry-roll-drift 0";

/// x y z qx qy qz qw of a data row (columns 2-8 of both files).
std::vector<double> poseOf(const std::vector<std::string>& row) {
  std::vector<double> pose;
  for (int c = 2; c <= 8; ++c) pose.push_back(std::stod(row.at(c)));
  return pose;
}

/// The largest difference of two x y z qx qy qz qw poses; q and -q are the
/// same rotation.
double poseDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double position = 0, same = 0, opposite = 0;
  for (int i = 0; i < 3; ++i) position = std::max(position, std::abs(a[i] - b[i]));
  for (int i = 3; i < 7; ++i) {
    same = std::max(same, std::abs(a[i] - b[i]));
    opposite = std::max(opposite, std::abs(a[i] + b[i]));
  }
  return std::max(position, std::min(same, opposite));
}

class GeneratePipeSequence : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_EQ(run("rm -rf " + kDir + " && mkdir -p " + kDir), 0);
    // Default odometry noise, bag and images.
    ASSERT_EQ(
        run(kGenerator + kSequence + " --images " + kDir + "/drift --bag " + kDir + "/drift.bag",
            kDir + "/drift.log"),
        0)
        << readAll(kDir + "/drift.log");
    // Two missions: the second slower, every other option the default.
    ASSERT_EQ(run(kGenerator + kSequence + " --again-speed 0.8 --images " + kDir + "/again --bag " +
                      kDir + "/again.bag",
                  kDir + "/again.log"),
              0)
        << readAll(kDir + "/again.log");
    // Every odometry noise off.
    ASSERT_EQ(run(kGenerator + kSequence + kNoOdometryNoise + " --images " + kDir + "/exact",
                  kDir + "/exact.log"),
              0)
        << readAll(kDir + "/exact.log");
  }
};

TEST_F(GeneratePipeSequence, IntrinsicsCsvHoldsTheRenderersCamera) {
  // 64 x 48 at the default 90 deg horizontal field of view: fx = fy = 32
  // (half the width), the centre of the pixel grid (31.5, 23.5).
  EXPECT_EQ(readAll(kDir + "/drift/intrinsics.csv"), "fx,fy,cx,cy\n32,32,31.5,23.5\n");
}

TEST_F(GeneratePipeSequence, OdometryCsvHasThePosesFramesAndStampsAndStartsAtTheTruth) {
  const Table poses = readCsv(kDir + "/drift/poses.csv");
  const Table odometry = readCsv(kDir + "/drift/odometry.csv");
  ASSERT_EQ(poses.size(), 61u);  // header and 60 frames
  ASSERT_EQ(odometry.size(), poses.size());
  EXPECT_EQ(odometry[0],
            (std::vector<std::string>{"frame", "stamp", "x", "y", "z", "qx", "qy", "qz", "qw"}));
  for (std::size_t i = 1; i < poses.size(); ++i) {
    SCOPED_TRACE(i);
    ASSERT_EQ(odometry[i].size(), 9u);
    EXPECT_EQ(odometry[i][0], poses[i][0]);  // frame
    EXPECT_EQ(odometry[i][1], poses[i][1]);  // stamp
  }
  // The first row is the first pose, digit for digit; then the odometry
  // drifts away (by centimetres after 6 m with the default noise).
  EXPECT_EQ(std::vector<std::string>(odometry[1].begin() + 2, odometry[1].end()),
            std::vector<std::string>(poses[1].begin() + 2, poses[1].begin() + 9));
  EXPECT_GT(poseDifference(poseOf(odometry.back()), poseOf(poses.back())), 0.01);
}

TEST_F(GeneratePipeSequence, WithoutNoiseTheOdometryIsPosesCsv) {
  const Table poses = readCsv(kDir + "/exact/poses.csv");
  const Table odometry = readCsv(kDir + "/exact/odometry.csv");
  ASSERT_EQ(poses.size(), 61u);
  ASSERT_EQ(odometry.size(), poses.size());
  for (std::size_t i = 1; i < poses.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(odometry[i][0], poses[i][0]);
    EXPECT_EQ(odometry[i][1], poses[i][1]);
    // Both printed with 6 decimals: equal up to the rounding of the last.
    EXPECT_LE(poseDifference(poseOf(odometry[i]), poseOf(poses[i])), 1.5e-6);
  }
  EXPECT_NE(readAll(kDir + "/exact.log").find("odometry: end-point drift 0.000 m (0.00 %"),
            std::string::npos)
      << readAll(kDir + "/exact.log");
}

TEST_F(GeneratePipeSequence, TheOdometryOptionsChangeNothingElse) {
  EXPECT_EQ(readAll(kDir + "/drift/poses.csv"), readAll(kDir + "/exact/poses.csv"));
  EXPECT_EQ(readAll(kDir + "/drift/frame_000059.png"), readAll(kDir + "/exact/frame_000059.png"));
}

TEST_F(GeneratePipeSequence, TheBagHasTheOdometryOnOdomAndTheTruthAsOdometry) {
  rosbag::Bag bag(kDir + "/drift.bag", rosbag::bagmode::Read);
  std::vector<nav_msgs::Odometry> odometry;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/odom"))) {
    const nav_msgs::Odometry::ConstPtr msg = m.instantiate<nav_msgs::Odometry>();
    ASSERT_TRUE(msg) << m.getDataType();
    odometry.push_back(*msg);
  }
  std::vector<geometry_msgs::PoseStamped> truth;
  for (const rosbag::MessageInstance& m :
       rosbag::View(bag, rosbag::TopicQuery("/ground_truth/pose"))) {
    truth.push_back(*m.instantiate<geometry_msgs::PoseStamped>());
  }
  std::vector<nav_msgs::Odometry> truth_odometry;
  for (const rosbag::MessageInstance& m :
       rosbag::View(bag, rosbag::TopicQuery("/ground_truth/odom"))) {
    const nav_msgs::Odometry::ConstPtr msg = m.instantiate<nav_msgs::Odometry>();
    ASSERT_TRUE(msg) << m.getDataType();
    truth_odometry.push_back(*msg);
  }
  const Table csv = readCsv(kDir + "/drift/odometry.csv");
  ASSERT_EQ(odometry.size(), 60u);
  ASSERT_EQ(truth.size(), odometry.size());
  ASSERT_EQ(truth_odometry.size(), truth.size());
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    SCOPED_TRACE(i);
    // The ground truth as nav_msgs/Odometry: the PoseStamped's pose.
    EXPECT_EQ(truth_odometry[i].header.stamp, truth[i].header.stamp);
    EXPECT_EQ(truth_odometry[i].header.frame_id, "map");
    EXPECT_EQ(truth_odometry[i].child_frame_id, "camera_link");
    EXPECT_EQ(truth_odometry[i].pose.pose, truth[i].pose);
    const nav_msgs::Odometry& o = odometry[i];
    EXPECT_EQ(o.header.seq, i);
    EXPECT_EQ(o.header.stamp, truth[i].header.stamp);
    EXPECT_EQ(o.header.frame_id, "odom");
    EXPECT_EQ(o.child_frame_id, "camera_link");
    const geometry_msgs::Pose& p = o.pose.pose;
    EXPECT_LE(poseDifference({p.position.x, p.position.y, p.position.z, p.orientation.x,
                              p.orientation.y, p.orientation.z, p.orientation.w},
                             poseOf(csv[i + 1])),
              1e-6);
    // A covariance: symmetric, a variance on every axis once the rotation
    // noise of the first step has moved the second (the default noise has
    // all four kinds).
    for (int r = 0; r < 6; ++r) {
      EXPECT_GE(o.pose.covariance[7 * r], 0);
      if (i > 1) EXPECT_GT(o.pose.covariance[7 * r], 0) << r;
      for (int c = 0; c < 6; ++c) {
        EXPECT_NEAR(o.pose.covariance[6 * r + c], o.pose.covariance[6 * c + r], 1e-12);
      }
    }
  }
  // Frame 0: the odometry starts at the true pose, with nothing to doubt.
  EXPECT_EQ(odometry[0].pose.pose, truth[0].pose);
  for (double v : odometry[0].pose.covariance) EXPECT_EQ(v, 0);
}

TEST_F(GeneratePipeSequence, TheSummaryAndTheGroundTruthHeaderReportTheDrift) {
  const std::string log = readAll(kDir + "/drift.log");
  EXPECT_NE(log.find("odometry: end-point drift "), std::string::npos) << log;
  EXPECT_NE(log.find("% of the metres driven); slip 0.03, slip noise 0.02, heading drift 1"),
            std::string::npos)
      << log;
  const std::string gt = readAll(kDir + "/drift_gt.txt");
  EXPECT_NE(gt.find("# odometry (odometry.csv, /odom): end-point drift "), std::string::npos) << gt;
}

TEST_F(GeneratePipeSequence, TheSeedDecidesTheOdometryNoise) {
  const std::string dir = kDir + "/seed2";
  ASSERT_EQ(run(kGenerator + kSequence + " --seed 2 --images " + dir, kDir + "/seed2.log"), 0)
      << readAll(kDir + "/seed2.log");
  // Other poses too (the roll is the seed's); what matters is the drift:
  // the odometry's offset from the truth differs.
  const Table poses1 = readCsv(kDir + "/drift/poses.csv");
  const Table odometry1 = readCsv(kDir + "/drift/odometry.csv");
  const Table poses2 = readCsv(dir + "/poses.csv"), odometry2 = readCsv(dir + "/odometry.csv");
  ASSERT_EQ(odometry2.size(), odometry1.size());
  const double x1 = std::stod(odometry1.back()[2]) - std::stod(poses1.back()[2]);
  const double x2 = std::stod(odometry2.back()[2]) - std::stod(poses2.back()[2]);
  EXPECT_GT(std::abs(x1 - x2), 1e-4) << x1 << " " << x2;
}

TEST_F(GeneratePipeSequence, BadOdometryOptionsAreRefusedNamingTheFlag) {
  const std::string log = kDir + "/bad.log";
  const auto refused = [&](const std::string& options, const std::string& flag) {
    EXPECT_NE(run(kGenerator + " --images " + kDir + "/bad --frames 2 " + options, log), 0)
        << options;
    EXPECT_NE(readAll(log).find(flag), std::string::npos) << options << ": " << readAll(log);
  };
  refused("--odometry-slip 0.6", "--odometry-slip must be in [-0.5, 0.5]");
  refused("--odometry-slip -0.51", "--odometry-slip must be in [-0.5, 0.5]");
  refused("--odometry-slip nan", "--odometry-slip");
  refused("--odometry-slip-noise -0.1", "--odometry-slip-noise must be >= 0");
  refused("--odometry-heading-drift -1", "--odometry-heading-drift must be >= 0");
  refused("--odometry-roll-drift inf", "--odometry-roll-drift");
  refused("--odometry-roll-drift", "--odometry-roll-drift: missing value");
}

const char kOneMission[] = "# first_frame,mission_id,name\n0,1,first survey\n";

TEST_F(GeneratePipeSequence, MissionsCsvIsWrittenForEverySequence) {
  EXPECT_EQ(readAll(kDir + "/drift/missions.csv"), kOneMission);
  EXPECT_EQ(readAll(kDir + "/drift_missions.csv"), kOneMission);
  EXPECT_EQ(readAll(kDir + "/exact/missions.csv"), kOneMission);
  const std::string two = std::string(kOneMission) + "60,2,second survey\n";
  EXPECT_EQ(readAll(kDir + "/again/missions.csv"), two);
  EXPECT_EQ(readAll(kDir + "/again_missions.csv"), two);
}

TEST_F(GeneratePipeSequence, AgainContinuesFramesStampsAndTheOdometer) {
  const Table poses = readCsv(kDir + "/again/poses.csv");
  ASSERT_EQ(poses.size(), 121u);  // 60 frames per mission
  for (std::size_t i = 1; i < poses.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(std::stoi(poses[i][0]), static_cast<int>(i) - 1);
    if (i > 1) {
      EXPECT_GT(std::stod(poses[i][1]), std::stod(poses[i - 1][1]));    // stamp
      EXPECT_GE(std::stod(poses[i][12]), std::stod(poses[i - 1][12]));  // odometer
    }
  }
  // The second mission drives from the start of the route again, 8 cm per
  // frame (0.8 m/s at 10 Hz) instead of 10.
  EXPECT_EQ(poses[61][11], "0.000000");
  EXPECT_EQ(poses[62][11], "0.080000");
  EXPECT_NE(readAll(kDir + "/again/frame_000119.png"), "");
  // The readers of the evaluation take both files (never-decreasing
  // odometer, frames in order).
  EXPECT_EQ(eval::readOdometry(kDir + "/again/poses.csv").size(), 120u);
  EXPECT_EQ(eval::readOdometry(kDir + "/again/odometry.csv").size(), 120u);
  EXPECT_EQ(eval::readOdometryPoses(kDir + "/again/odometry.csv").size(), 120u);
}

TEST_F(GeneratePipeSequence, AgainLeavesTheFirstMissionAsWithoutIt) {
  const Table once = readCsv(kDir + "/drift/poses.csv");
  const Table again = readCsv(kDir + "/again/poses.csv");
  const Table once_odometry = readCsv(kDir + "/drift/odometry.csv");
  const Table again_odometry = readCsv(kDir + "/again/odometry.csv");
  for (std::size_t i = 0; i < once.size(); ++i) {
    EXPECT_EQ(again[i], once[i]) << i;
    EXPECT_EQ(again_odometry[i], once_odometry[i]) << i;
  }
  EXPECT_EQ(readAll(kDir + "/again/frame_000059.png"), readAll(kDir + "/drift/frame_000059.png"));
}

TEST_F(GeneratePipeSequence, TheSecondMissionsOdometryStartsANewFrame) {
  const Table poses = readCsv(kDir + "/again/poses.csv");
  const Table odometry = readCsv(kDir + "/again/odometry.csv");
  ASSERT_EQ(odometry.size(), poses.size());
  // Frame 60 (row 61): the odometry starts afresh at the true pose, as the
  // first mission's did at frame 0; the first mission's drift is gone.
  EXPECT_EQ(std::vector<std::string>(odometry[61].begin() + 2, odometry[61].end()),
            std::vector<std::string>(poses[61].begin() + 2, poses[61].begin() + 9));
  EXPECT_GT(poseDifference(poseOf(odometry[60]), poseOf(poses[60])), 0.01);
  // The bag: 120 frames on /odom, the /odometer counting on without the
  // jump between the two missions' positions.
  rosbag::Bag bag(kDir + "/again.bag", rosbag::bagmode::Read);
  std::vector<double> odometer;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/odometer"))) {
    odometer.push_back(m.instantiate<std_msgs::Float64>()->data);
  }
  int odom = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/odom"))) {
    odom += m.instantiate<nav_msgs::Odometry>() ? 1 : 0;
  }
  EXPECT_EQ(odom, 120);
  ASSERT_EQ(odometer.size(), 120u);
  EXPECT_EQ(odometer[60], odometer[59]);
  for (std::size_t i = 1; i < odometer.size(); ++i) EXPECT_GE(odometer[i], odometer[i - 1]) << i;
}

TEST_F(GeneratePipeSequence, TheSecondMissionsQueriesMatchTheFirstMission) {
  const eval::GroundTruth gt = eval::readGroundTruth(kDir + "/again_gt.txt");
  int cross = 0;
  for (const auto& kv : gt.loops) {
    EXPECT_GE(kv.first, 60) << "the first mission drives 6 m of new pipe";
    if (!kv.second.empty() && kv.second.front() < 60) ++cross;
  }
  // The second mission drives 4.8 m of the first's 6 m: nearly every query
  // sees a place of the first mission.
  EXPECT_GE(cross, 50);
  const std::string header = readAll(kDir + "/again_gt.txt");
  EXPECT_NE(header.find("# mission 2 (second survey, missions.csv) from frame 60: seed 1001, "
                        "speed 0.8 m/s"),
            std::string::npos)
      << header;
}

TEST_F(GeneratePipeSequence, TheUsageDescribesTheAgainOptions) {
  ASSERT_EQ(run(kGenerator + " --help", kDir + "/help.log"), 0);
  const std::string usage = readAll(kDir + "/help.log");
  for (const char* flag : {"--again ", "--again-marks-changed F", "--again-seed N",
                           "--again-speed MPS", "--again-route-nodes LIST"}) {
    EXPECT_NE(usage.find(flag), std::string::npos) << flag;
  }
}

TEST_F(GeneratePipeSequence, BadAgainOptionsAreRefusedNamingTheFlag) {
  const std::string log = kDir + "/bad_again.log";
  const auto refused = [&](const std::string& options, const std::string& message) {
    EXPECT_NE(run(kGenerator + " --images " + kDir + "/bad_again --frames 2 " + options, log), 0)
        << options;
    EXPECT_NE(readAll(log).find(message), std::string::npos) << options << ": " << readAll(log);
  };
  refused("--again-marks-changed 1.5", "--again-marks-changed must be in [0, 1], not 1.5");
  refused("--again-marks-changed -0.1", "--again-marks-changed must be in [0, 1]");
  refused("--again-marks-changed nan", "--again-marks-changed");
  refused("--again-speed -0.2", "--again-speed must be > 0, not -0.2");
  refused("--again-speed 0", "--again-speed must be > 0");
  refused("--speed -1", "--speed must be > 0, not -1");
  refused("--again-seed -1", "--again-seed must be >= 0");
  refused("--again-route-nodes 0,2", "--again-route-nodes 0,2: ");
  refused("--again-route-nodes", "--again-route-nodes: missing value");
}

}  // namespace
}  // namespace bowg
