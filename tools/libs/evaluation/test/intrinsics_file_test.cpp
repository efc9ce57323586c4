#include "bowg_evaluation/intrinsics_file.h"

#include <gtest/gtest.h>

#include "bowg/core/errors.h"

namespace bowg {
namespace eval {
namespace {

std::string errorOf(const std::string& text) {
  try {
    parseIntrinsics(text, "intrinsics.csv");
  } catch (const FormatError& e) {
    return e.what();
  }
  return "";
}

TEST(IntrinsicsFile, ReadsWhatItWrites) {
  CameraIntrinsics k;
  k.valid = true;
  k.fx = 320;
  k.fy = 321.25;
  k.cx = 319.5;
  k.cy = 239.5;
  EXPECT_EQ(intrinsicsToCsv(k), "fx,fy,cx,cy\n320,321.25,319.5,239.5\n");
  const CameraIntrinsics back = parseIntrinsics(intrinsicsToCsv(k), "x");
  EXPECT_TRUE(back.valid);
  EXPECT_EQ(back.fx, 320);
  EXPECT_EQ(back.fy, 321.25);
  EXPECT_EQ(back.cx, 319.5);
  EXPECT_EQ(back.cy, 239.5);
}

TEST(IntrinsicsFile, BadFilesNameTheFileAndLine) {
  EXPECT_EQ(errorOf("f,c\n1,2\n"), "intrinsics.csv:1: expected the header 'fx,fy,cx,cy'");
  EXPECT_EQ(errorOf("fx,fy,cx,cy\n"), "intrinsics.csv:1: no row after the header");
  EXPECT_EQ(errorOf("fx,fy,cx,cy\n1,2,3\n"), "intrinsics.csv:2: expected 4 cells, got 3");
  EXPECT_EQ(errorOf("fx,fy,cx,cy\n1,2,x,4\n"), "intrinsics.csv:2: 'x' is not a finite number");
  EXPECT_EQ(errorOf("fx,fy,cx,cy\n0,2,3,4\n"), "intrinsics.csv:2: fx and fy must be > 0");
  EXPECT_EQ(errorOf("fx,fy,cx,cy\n1,2,3,4\n1,2,3,4\n"), "intrinsics.csv:3: one row expected");
  EXPECT_THROW(readIntrinsics("/nonexistent/intrinsics.csv"), IoError);
}

}  // namespace
}  // namespace eval
}  // namespace bowg
