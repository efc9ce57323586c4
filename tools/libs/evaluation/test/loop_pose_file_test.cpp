#include "bowg_evaluation/loop_pose_file.h"

#include <gtest/gtest.h>

#include <string>

#include "bowg/core/errors.h"

namespace bowg {
namespace eval {
namespace {

const std::string kHeader =
    "query,match,metric_status,r00,r01,r02,r10,r11,r12,r20,r21,r22,tx,ty,tz,cxx,cxy,cxz,cyy,cyz,"
    "czz\n";

std::string errorOf(const std::string& text) {
  try {
    parseLoopPosesCsv(text, "loop_poses.csv");
  } catch (const FormatError& e) {
    return e.what();
  }
  return "";
}

TEST(LoopPoseFile, WritesAndReadsBackEveryField) {
  LoopPose a;
  a.query = 420;
  a.match = 17;
  a.metric_status = "estimated";
  const double R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};  // 90 deg about z
  std::copy(R, R + 9, a.rotation);
  a.translation[0] = 0.125;
  a.translation[1] = -0.03;
  a.translation[2] = 0.5;
  const double C[9] = {4e-4, 1e-5, -2e-5, 1e-5, 9e-4, 3e-6, -2e-5, 3e-6, 2.5e-3};
  std::copy(C, C + 9, a.covariance);
  LoopPose b;  // a unit direction, scale unknown
  b.query = 421;
  b.match = 18;
  b.metric_status = "no_neighbour";
  b.translation[2] = 1;
  const std::string csv = loopPosesToCsv({a, b});
  EXPECT_EQ(csv.substr(0, kHeader.size()), kHeader);
  const std::vector<LoopPose> back = parseLoopPosesCsv(csv, "x");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].query, 420);
  EXPECT_EQ(back[0].match, 17);
  EXPECT_TRUE(back[0].metric());
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(back[0].rotation[i], R[i]);
    EXPECT_DOUBLE_EQ(back[0].covariance[i], C[i]);
  }
  EXPECT_DOUBLE_EQ(back[0].translation[0], 0.125);
  EXPECT_DOUBLE_EQ(back[0].translation[2], 0.5);
  EXPECT_FALSE(back[1].metric());
  EXPECT_EQ(back[1].metric_status, "no_neighbour");
  EXPECT_EQ(back[1].translation[2], 1.0);
}

TEST(LoopPoseFile, BadFilesNameTheFileAndLine) {
  const std::string ok = "3,1,estimated,1,0,0,0,1,0,0,0,1,0.1,0,0,1e-4,0,0,1e-4,0,1e-4\n";
  EXPECT_EQ(errorOf(kHeader + ok), "");
  EXPECT_NE(errorOf("query,match\n" + ok).find("loop_poses.csv:1: expected the header"),
            std::string::npos);
  EXPECT_EQ(errorOf(kHeader + "3,1,estimated,1,0,0\n"),
            "loop_poses.csv:2: expected 21 cells, got 6");
  EXPECT_EQ(errorOf(kHeader + "3,1,estimated,1,0,0,0,1,0,0,0,1,x,0,0,1e-4,0,0,1e-4,0,1e-4\n"),
            "loop_poses.csv:2: cell 13 'x' is not a finite number");
  EXPECT_EQ(errorOf(kHeader + "-3,1,estimated,1,0,0,0,1,0,0,0,1,0.1,0,0,1e-4,0,0,1e-4,0,1e-4\n"),
            "loop_poses.csv:2: query and match must be non-negative integers");
  EXPECT_EQ(errorOf(kHeader + "3,1,estimated,2,0,0,0,1,0,0,0,1,0.1,0,0,1e-4,0,0,1e-4,0,1e-4\n"),
            "loop_poses.csv:2: r00..r22 is not a rotation");
  EXPECT_EQ(errorOf(kHeader + "3,1,estimated,1,0,0,0,1,0,0,0,1,0.1,0,0,0,0,0,1e-4,0,1e-4\n"),
            "loop_poses.csv:2: a metric translation needs a covariance with a positive diagonal");
  // Without the metric translation the covariance is zero.
  EXPECT_EQ(errorOf(kHeader + "3,1,no_odometry,1,0,0,0,1,0,0,0,1,1,0,0,0,0,0,0,0,0\n"), "");
}

}  // namespace
}  // namespace eval
}  // namespace bowg
