// Which acceptance a keyframe's odometry selects (odometry_input.h).
#include "bowg/detection/odometry_input.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace bowg {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

OdometryPosition at(double x, double y, double z) {
  OdometryPosition p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

TEST(OdometryInput, PositionsNeedAnOdometerAndAnOdometerNeedsNothingElse) {
  EXPECT_EQ(odometryInput(3.5, at(1, 2, 0)), OdometryInput::kPositions);
  EXPECT_EQ(odometryInput(0.0, at(0, 0, 0)), OdometryInput::kPositions);
  EXPECT_EQ(odometryInput(3.5, OdometryPosition()), OdometryInput::kOdometer);
  // A position alone places nothing: the gates need the metres driven.
  EXPECT_EQ(odometryInput(kNaN, at(1, 2, 0)), OdometryInput::kNone);
  EXPECT_EQ(odometryInput(kNaN, OdometryPosition()), OdometryInput::kNone);
  EXPECT_EQ(odometryInput(std::numeric_limits<double>::infinity(), OdometryPosition()),
            OdometryInput::kNone);
}

TEST(OdometryInput, NamesAndStartUpLines) {
  EXPECT_STREQ(toString(OdometryInput::kPositions), "positions");
  EXPECT_STREQ(toString(OdometryInput::kOdometer), "odometer");
  EXPECT_STREQ(toString(OdometryInput::kNone), "none");
  // Each line says what the input is, then what the detector does with it.
  EXPECT_EQ(
      std::string(describeAcceptance(OdometryInput::kPositions)).find("positions and odometer: "),
      0u);
  EXPECT_EQ(std::string(describeAcceptance(OdometryInput::kOdometer)).find("odometer only: "), 0u);
  EXPECT_EQ(std::string(describeAcceptance(OdometryInput::kNone)).find("none: "), 0u);
  EXPECT_NE(std::string(describeAcceptance(OdometryInput::kNone)).find("min_keyframe_interval"),
            std::string::npos);
  // Only where positions gate the match do the chain's unique inliers count
  // on average.
  EXPECT_NE(std::string(describeAcceptance(OdometryInput::kPositions)).find("on average"),
            std::string::npos);
  EXPECT_EQ(std::string(describeAcceptance(OdometryInput::kOdometer)).find("on average"),
            std::string::npos);
  EXPECT_EQ(std::string(describeAcceptance(OdometryInput::kNone)).find("on average"),
            std::string::npos);
}

}  // namespace
}  // namespace bowg
