#include "bowg_evaluation/ground_truth.h"

#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "bowg/core/errors.h"

namespace bowg {
namespace eval {
namespace {

std::string formatErrorOf(const std::string& text) {
  try {
    parseGroundTruth(text, "gt.txt");
  } catch (const FormatError& e) {
    return e.what();
  }
  return "no error";
}

TEST(GroundTruthTest, ParsesTheCommonFormat) {
  const GroundTruth gt = parseGroundTruth(
      "# a comment\n"
      "\n"
      "12: 3,4, 5   # trailing comment\n"
      "  20 :7\n"
      "21:\n"
      "30: 9,8,9\r\n",
      "gt.txt");
  EXPECT_TRUE(gt.contains(12, 4));
  EXPECT_FALSE(gt.contains(12, 6));
  EXPECT_TRUE(gt.contains(20, 7));
  EXPECT_FALSE(gt.hasLoop(21));  // explicitly empty
  EXPECT_FALSE(gt.hasLoop(13));  // not listed
  EXPECT_EQ(gt.loops.at(30), (std::vector<int>{8, 9}));  // sorted, unique
  EXPECT_EQ(gt.positives(), 3);  // 12, 20, 30
}

TEST(GroundTruthTest, MalformedLinesNameTheFileLineAndProblem) {
  EXPECT_NE(formatErrorOf("12 3,4\n").find("gt.txt:1: expected '<query>: <match>"), std::string::npos);
  EXPECT_NE(formatErrorOf("\nx: 3\n").find("gt.txt:2: the query 'x'"), std::string::npos);
  EXPECT_NE(formatErrorOf("12: 3,a\n").find("the match 'a'"), std::string::npos);
  EXPECT_NE(formatErrorOf("12: 3,-4\n").find("the match '-4'"), std::string::npos);
  EXPECT_NE(formatErrorOf("12: 3,,4\n").find("the match ''"), std::string::npos);
  EXPECT_NE(formatErrorOf("12: 3,4,\n").find("trailing comma"), std::string::npos);
  EXPECT_NE(formatErrorOf("12: 12\n").find("not an earlier frame"), std::string::npos);
  EXPECT_NE(formatErrorOf("12: 3\n12: 4\n").find("gt.txt:2: query 12 appears twice"), std::string::npos);
  EXPECT_THROW(readGroundTruth("/nonexistent/gt.txt"), IoError);
}

TEST(GroundTruthTest, WriteThenReadGivesTheSameSets) {
  GroundTruth gt;
  gt.loops[5] = {1, 2};
  gt.loops[9] = {};
  gt.loops[40] = {7};
  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/gt_roundtrip.txt";
  writeGroundTruth(path, gt, "first line\nsecond line");
  const GroundTruth back = readGroundTruth(path);
  EXPECT_EQ(back.loops.size(), 2u);  // the empty set is not written
  EXPECT_EQ(back.loops.at(5), (std::vector<int>{1, 2}));
  EXPECT_EQ(back.loops.at(40), (std::vector<int>{7}));
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "# first line");
}

TravelPose pose(double x, double y, double heading_deg, double distance) {
  TravelPose p;
  p.x = x;
  p.y = y;
  p.hx = std::cos(heading_deg * M_PI / 180);
  p.hy = std::sin(heading_deg * M_PI / 180);
  p.distance = distance;
  return p;
}

TEST(GroundTruthTest, FromPosesUsesPositionHeadingAndRecentExclusion) {
  // Defaults: < 0.15 m, < 30 deg, at least 3 m driven in between.
  const std::vector<TravelPose> poses = {
      pose(0, 0, 0, 0),        // 0
      pose(5, 0, 0, 5),        // 1
      pose(0.1, 0, 0, 10),     // 2: 0.1 m from 0, same heading -> {0}
      pose(0.05, 0, 180, 10.05),  // 3: opposite heading -> {} (2 is too recent anyway)
      pose(0, 0.2, 0, 15),     // 4: 0.2 m from everything -> {}
      pose(0, 0.1, 20, 20),    // 5: 0 (0.1 m, 20 deg), 2 (0.141 m), 4 (0.1 m) -> {0, 2, 4}
      pose(0.1, 0, 0, 21),     // 6: 0, 2; 5 driven 1 m ago (too recent); 4 is 0.224 m away
  };
  const GroundTruth gt = groundTruthFromPoses(poses, GroundTruthOptions());
  EXPECT_EQ(gt.loops.at(2), (std::vector<int>{0}));
  EXPECT_FALSE(gt.hasLoop(3));
  EXPECT_FALSE(gt.hasLoop(4));
  EXPECT_EQ(gt.loops.at(5), (std::vector<int>{0, 2, 4}));
  EXPECT_EQ(gt.loops.at(6), (std::vector<int>{0, 2}));
  EXPECT_EQ(gt.positives(), 3);
  // A 10 deg heading tolerance drops the 20 deg revisits of frame 5.
  GroundTruthOptions narrow;
  narrow.max_heading_deg = 10;
  EXPECT_FALSE(groundTruthFromPoses(poses, narrow).hasLoop(5));
  GroundTruthOptions bad;
  bad.max_distance_m = 0;
  EXPECT_THROW(groundTruthFromPoses(poses, bad), std::invalid_argument);
}

}  // namespace
}  // namespace eval
}  // namespace bowg
