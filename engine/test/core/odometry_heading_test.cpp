// The heading of an odometry orientation (odometry_heading.h) on rotations
// worked out by hand.
#include "bowg/core/odometry_heading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace bowg {
namespace {

void expectHeading(const OdometryHeading& h, double x, double y, double z) {
  ASSERT_TRUE(h.known());
  EXPECT_NEAR(h.x, x, 1e-6);
  EXPECT_NEAR(h.y, y, 1e-6);
  EXPECT_NEAR(h.z, z, 1e-6);
}

TEST(OdometryHeading, IsTheBodysForwardAxis) {
  const double s45 = std::sqrt(0.5);
  // Identity: facing +x.
  expectHeading(headingFromQuaternion(0, 0, 0, 1), 1, 0, 0);
  // Yaw +90 deg about z, q = (0, 0, sin 45, cos 45): x turns to +y
  // (1 - 2 * 0.5, 2 * 0.5, 0).
  expectHeading(headingFromQuaternion(0, 0, s45, s45), 0, 1, 0);
  // Pitch +90 deg about y, q = (0, sin 45, 0, cos 45): x turns to -z
  // (1 - 2 * 0.5, 0, -2 * 0.5).
  expectHeading(headingFromQuaternion(0, s45, 0, s45), 0, 0, -1);
  // Roll 60 deg about x, q = (sin 30, 0, 0, cos 30): the forward axis stays.
  expectHeading(headingFromQuaternion(0.5, 0, 0, std::sqrt(0.75)), 1, 0, 0);
  // Yaw 180 deg: q = (0, 0, 1, 0), and -q is the same rotation.
  expectHeading(headingFromQuaternion(0, 0, 1, 0), -1, 0, 0);
  expectHeading(headingFromQuaternion(0, 0, -1, 0), -1, 0, 0);
}

TEST(OdometryHeading, ANearlyUnitQuaternionIsScaledAndAGarbledOneIsNoHeading) {
  // Norm 1.005: within 0.01 of 1, scaled to unit length.
  expectHeading(headingFromQuaternion(0, 0, 0, 1.005), 1, 0, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(headingFromQuaternion(0, 0, 0, 0).unknown());  // "no orientation"
  EXPECT_TRUE(headingFromQuaternion(0, 0, 0, 2).unknown());
  EXPECT_TRUE(headingFromQuaternion(0, 0, 0, 0.98).unknown());
  EXPECT_TRUE(headingFromQuaternion(nan, 0, 0, 1).unknown());
  EXPECT_TRUE(headingFromQuaternion(0, 0, 0, std::numeric_limits<double>::infinity()).unknown());
}

TEST(OdometryHeading, AngleBetweenHeadings) {
  OdometryHeading x, y, back, thirty;
  x.x = 1, x.y = 0, x.z = 0;
  y.x = 0, y.y = 1, y.z = 0;
  back.x = -1, back.y = 0, back.z = 0;
  thirty.x = static_cast<float>(std::sqrt(0.75)), thirty.y = 0.5f, thirty.z = 0;
  EXPECT_NEAR(headingAngleDeg(x, x), 0.0, 1e-3);
  EXPECT_NEAR(headingAngleDeg(x, y), 90.0, 1e-4);
  EXPECT_NEAR(headingAngleDeg(x, back), 180.0, 1e-4);
  EXPECT_NEAR(headingAngleDeg(thirty, x), 30.0, 1e-4);
  EXPECT_NEAR(headingAngleDeg(thirty, y), 60.0, 1e-4);
}

TEST(OdometryHeading, ValidIsUnknownOrUnitLength) {
  OdometryHeading h;
  EXPECT_TRUE(h.valid());  // unknown
  h.x = 1.f;
  EXPECT_FALSE(h.valid());  // partly known
  h.y = 0.f, h.z = 0.f;
  EXPECT_TRUE(h.valid());
  h.x = 2.f;
  EXPECT_FALSE(h.valid());  // not a direction
}

}  // namespace
}  // namespace bowg
