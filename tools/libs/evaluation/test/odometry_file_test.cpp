#include "bowg_evaluation/odometry_file.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "bowg/core/errors.h"

namespace bowg {
namespace eval {
namespace {

// The message of the FormatError `parse` throws on `text`; "" when none.
template <typename Parse>
std::string messageOf(Parse parse, const std::string& text) {
  try {
    parse(text);
  } catch (const FormatError& e) {
    return e.what();
  }
  return "";
}

std::string errorOf(const std::string& text) {
  return messageOf([](const std::string& t) { parseOdometry(t, "poses.csv"); }, text);
}

std::string positionErrorOf(const std::string& text) {
  return messageOf([](const std::string& t) { parseOdometryPoses(t, "odometry.csv"); }, text);
}

TEST(OdometryFile, ReadsTheOdometerColumnOfTheGeneratorsPoses) {
  const std::string text =
      "frame,stamp,x,distance,odometer\n"
      "0,1.0,0.0,0.00,0.00\n"
      "1,1.5,0.1,0.10,0.10\n"
      "2,2.0,0.05,0.05,0.15\n";  // backing up: distance falls, odometer grows
  const std::vector<double> o = parseOdometry(text, "poses.csv");
  ASSERT_EQ(o.size(), 3u);
  EXPECT_DOUBLE_EQ(o[0], 0.0);
  EXPECT_DOUBLE_EQ(o[1], 0.1);
  EXPECT_DOUBLE_EQ(o[2], 0.15);
}

TEST(OdometryFile, FallsBackToDistanceAndLeavesMissingFramesUnknown) {
  const std::vector<double> o = parseOdometry("frame, distance\n1, 2.5\n\n4, 3.0\n", "p");
  ASSERT_EQ(o.size(), 5u);
  EXPECT_TRUE(std::isnan(o[0]));
  EXPECT_DOUBLE_EQ(o[1], 2.5);
  EXPECT_TRUE(std::isnan(o[2]));
  EXPECT_TRUE(std::isnan(o[3]));
  EXPECT_DOUBLE_EQ(o[4], 3.0);
}

TEST(OdometryFile, APoseFileGivesThePathLengthThroughItsPositions) {
  // The drifting odometry.csv: steps of 0.3 (3-4-5 scaled), 0.1 back along
  // x (backing up counts as driven), then 0.2 along z.
  const std::string text =
      "frame,stamp,x,y,z,qx,qy,qz,qw\n"
      "0,0.0,1.0,2.0,0.0,0,0,0,1\n"
      "1,0.5,1.18,2.24,0.0,0,0,0,1\n"
      "2,1.0,1.08,2.24,0.0,0,0,0,1\n"
      "4,2.0,1.08,2.24,0.2,0,0,0,1\n";
  const std::vector<double> o = parseOdometry(text, "odometry.csv");
  ASSERT_EQ(o.size(), 5u);
  EXPECT_DOUBLE_EQ(o[0], 0.0);
  EXPECT_NEAR(o[1], 0.3, 1e-12);
  EXPECT_NEAR(o[2], 0.4, 1e-12);
  EXPECT_TRUE(std::isnan(o[3]));
  EXPECT_NEAR(o[4], 0.6, 1e-12);
  EXPECT_EQ(errorOf("frame,x,y,z\n0,1,2,inf\n"),
            "poses.csv:2: position 'inf' is not a finite number");
}

TEST(OdometryFile, BadFilesNameTheFileAndLine) {
  EXPECT_EQ(errorOf("frame,x\n0,1\n"),
            "poses.csv:1: the header needs a 'frame' column and an 'odometer' (or 'distance') "
            "column, or x, y and z");
  EXPECT_EQ(errorOf("frame,odometer\n0,1\n1,0.5\n"),
            "poses.csv:3: the odometer decreases (0.5 after 1.000000)");
  EXPECT_EQ(errorOf("frame,odometer\n0,-1\n"),
            "poses.csv:2: odometer '-1' is not a finite number >= 0");
  EXPECT_EQ(errorOf("frame,odometer\n0,nan\n"),
            "poses.csv:2: odometer 'nan' is not a finite number >= 0");
  EXPECT_EQ(errorOf("frame,odometer\n1,1\n1,2\n"),
            "poses.csv:3: frame 1 is not after the previous row's");
  EXPECT_EQ(errorOf("frame,odometer\n0.5,1\n"),
            "poses.csv:2: frame '0.5' is not a non-negative integer");
  EXPECT_EQ(errorOf("frame,odometer\n0\n"), "poses.csv:2: too few columns");
  EXPECT_THROW(readOdometry("/nonexistent/poses.csv"), IoError);
}

TEST(OdometryFile, PositionsOfAPoseFileAndUnknownFramesBetween) {
  const std::string text =
      "frame,stamp,x,y,z,qx,qy,qz,qw\n"
      "0,0.0,1.0,2.0,0.0,0,0,0,1\n"
      "2,1.0,1.08,-2.24,0.5,0,0,0,1\n";
  const std::vector<OdometryPose> poses = parseOdometryPoses(text, "odometry.csv");
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(poses[0].position.x, 1.0);
  EXPECT_EQ(poses[0].position.y, 2.0);
  EXPECT_EQ(poses[0].position.z, 0.0);
  EXPECT_TRUE(poses[1].position.unknown());
  EXPECT_TRUE(poses[1].heading.unknown());
  EXPECT_EQ(poses[2].position.x, 1.08);
  EXPECT_EQ(poses[2].position.y, -2.24);
  EXPECT_EQ(poses[2].position.z, 0.5);
  // The identity orientation faces +x.
  EXPECT_EQ(poses[2].heading.x, 1.f);
  EXPECT_EQ(poses[2].heading.y, 0.f);
  EXPECT_EQ(poses[2].heading.z, 0.f);
  EXPECT_EQ(positionErrorOf("frame,x,y\n0,1,2\n"),
            "odometry.csv:1: the header needs 'frame', 'x', 'y' and 'z' columns");
  EXPECT_EQ(positionErrorOf("frame,x,y,z\n0,1,nan,0\n"),
            "odometry.csv:2: position 'nan' is not a finite number");
  EXPECT_EQ(positionErrorOf("frame,x,y,z\n3,1,1,0\n2,1,1,0\n"),
            "odometry.csv:3: frame 2 is not after the previous row's");
  EXPECT_EQ(positionErrorOf("frame,x,y,z\n-1,1,1,0\n"),
            "odometry.csv:2: frame '-1' is not a non-negative integer");
  EXPECT_EQ(positionErrorOf("frame,x,y,z\n0,1,1\n"), "odometry.csv:2: too few columns");
}

TEST(OdometryFile, HeadingsOfAPoseFilesOrientations) {
  // Yaw +90 deg about z: q = (0, 0, sin 45, cos 45) faces +y.
  const std::string text =
      "frame,x,y,z,qx,qy,qz,qw\n"
      "0,0,0,0,0,0,0.7071068,0.7071068\n";
  const std::vector<OdometryPose> poses = parseOdometryPoses(text, "odometry.csv");
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_NEAR(poses[0].heading.x, 0.0, 1e-6);
  EXPECT_NEAR(poses[0].heading.y, 1.0, 1e-6);
  EXPECT_NEAR(poses[0].heading.z, 0.0, 1e-6);
  // Without a quaternion, positions and no heading.
  EXPECT_TRUE(parseOdometryPoses("frame,x,y,z\n0,1,2,3\n", "o.csv")[0].heading.unknown());
  EXPECT_EQ(positionErrorOf("frame,x,y,z,qz,qw\n0,0,0,0,0,1\n"),
            "odometry.csv:1: the header has some of 'qx', 'qy', 'qz', 'qw': an orientation needs "
            "all four");
  EXPECT_EQ(positionErrorOf("frame,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,0\n"),
            "odometry.csv:2: orientation (0, 0, 0, 0) is not a unit quaternion (qx, qy, qz, qw)");
  EXPECT_EQ(positionErrorOf("frame,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,w\n"),
            "odometry.csv:2: orientation 'w' is not a number");
  EXPECT_EQ(positionErrorOf("frame,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0\n"),
            "odometry.csv:2: too few columns");
}

}  // namespace
}  // namespace eval
}  // namespace bowg
