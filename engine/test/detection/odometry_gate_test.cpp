// The odometry gate (odometry_gate.h) on hand-worked positions.
#include "bowg/detection/odometry_gate.h"

#include <gtest/gtest.h>

#include <limits>

namespace bowg {
namespace {

DatabaseEntry at(double x, double y, double z, double odometer, std::uint32_t run = 0) {
  DatabaseEntry e;
  e.position.x = x;
  e.position.y = y;
  e.position.z = z;
  e.odometer = odometer;
  e.odometry_run = run;
  return e;
}

IslandOptions gate(double base_m, double drift) {
  IslandOptions o;
  o.odometry_gate_m = base_m;
  o.odometry_gate_drift = drift;
  return o;
}

TEST(OdometryGate, RadiusGrowsWithTheMetresDriven) {
  EXPECT_DOUBLE_EQ(odometryGateRadius(gate(0.5, 0.1), 0.0), 0.5);
  EXPECT_DOUBLE_EQ(odometryGateRadius(gate(0.5, 0.1), 20.0), 2.5);
  EXPECT_DOUBLE_EQ(odometryGateRadius(gate(0.5, 0.1), -20.0), 2.5);  // either order
  EXPECT_DOUBLE_EQ(odometryGateRadius(gate(1.0, 0.0), 300.0), 1.0);
}

TEST(OdometryGate, EntriesWithinTheRadiusPass) {
  const IslandOptions o = gate(0.5, 0.1);
  const DatabaseEntry query = at(0, 0, 0, 30.0);
  // 20 m driven apart: radius 2.5 m. (1.5, 2, 0) is 2.5 m away: on the
  // boundary, inside; (1.5, 2, 0.1) is sqrt(6.26) = 2.502 m: outside.
  EXPECT_TRUE(withinOdometryGate(query, at(1.5, 2, 0, 10.0), o));
  EXPECT_FALSE(withinOdometryGate(query, at(1.5, 2, 0.1, 10.0), o));
  // The same place 2 m driven apart: radius 0.7 m.
  EXPECT_TRUE(withinOdometryGate(query, at(0.6, 0, 0, 28.0), o));
  EXPECT_FALSE(withinOdometryGate(query, at(0.8, 0, 0, 28.0), o));
}

TEST(OdometryGate, WithoutComparablePositionsEverythingPasses) {
  const DatabaseEntry query = at(0, 0, 0, 30.0);
  const DatabaseEntry far = at(100, 0, 0, 29.0);
  EXPECT_FALSE(withinOdometryGate(query, far, gate(0.5, 0.1)));
  EXPECT_TRUE(withinOdometryGate(query, far, gate(0.0, 0.1)));  // gate off
  EXPECT_TRUE(withinOdometryGate(query, DatabaseEntry(), gate(0.5, 0.1)));  // unknown position
  EXPECT_TRUE(withinOdometryGate(DatabaseEntry(), far, gate(0.5, 0.1)));
  // Another odometry run: another frame, positions not comparable.
  EXPECT_TRUE(withinOdometryGate(query, at(100, 0, 0, 29.0, 1), gate(0.5, 0.1)));
  // Positions without odometers: no metres driven to scale the drift.
  DatabaseEntry no_odometer = far;
  no_odometer.odometer = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(withinOdometryGate(query, no_odometer, gate(0.5, 0.1)));
}

}  // namespace
}  // namespace bowg
