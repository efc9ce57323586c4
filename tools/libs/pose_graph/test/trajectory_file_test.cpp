// readTrajectory / parseTrajectory: columns by name, checks naming the line.
#include "bowg_pose_graph/trajectory_file.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bowg/core/errors.h"

namespace bowg {
namespace pose_graph {
namespace {

TEST(TrajectoryFile, ReadsColumnsByNameAndNormalisesQuaternions) {
  const std::vector<FramePose> p = parseTrajectory(
      "frame,stamp,x,y,z,qx,qy,qz,qw,roll_deg\n"
      "0,1.0,1,2,3,0,0,0,1,5\n"
      "\n"
      "2,1.2,4,5,6,0,0,0.7071068,0.7071068,0\n"
      "3,1.3,0,0,0,0,0,0,1.05,0\n",
      "t.csv");
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[1].frame, 2);
  EXPECT_DOUBLE_EQ(p[1].position[2], 6);
  // 90 deg about z: body x maps to world y.
  const Eigen::Vector3d x = p[1].isometry().linear() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(x.y(), 1.0, 1e-6);
  EXPECT_NEAR(p[2].quaternion[3], 1.0, 1e-12);  // 1.05 normalised
  EXPECT_NEAR(p[1].isometry().translation().x(), 4, 0);
}

TEST(TrajectoryFile, ErrorsNameTheFileLineAndProblem) {
  const auto message = [](const std::string& text) {
    try {
      parseTrajectory(text, "t.csv");
    } catch (const FormatError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("frame,x,y,z,qx,qy,qz\n0,0,0,0,0,0,0\n"),
            "t.csv:1: the header has no 'qw' column (needs frame,x,y,z,qx,qy,qz,qw)");
  EXPECT_EQ(message("frame,x,y,z,qx,qy,qz,qw\n0,0,nan,0,0,0,0,1\n"),
            "t.csv:2: y 'nan' is not a finite number");
  EXPECT_EQ(message("frame,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,1\n0,0,0,0,0,0,0,1\n"),
            "t.csv:3: frame 0 is not after the previous row's");
  EXPECT_EQ(message("frame,x,y,z,qx,qy,qz,qw\n-1,0,0,0,0,0,0,1\n"),
            "t.csv:2: frame '-1' is not a non-negative integer");
  EXPECT_EQ(message("frame,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,2\n"),
            "t.csv:2: the quaternion has length 2.000000, not ~1");
  EXPECT_EQ(message("frame,x,y,z,qx,qy,qz,qw\n0,0,0\n"), "t.csv:2: too few columns");
  EXPECT_THROW(readTrajectory("/nonexistent/poses.csv"), IoError);
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
