// The odometry gate (odometry_gate.h) on hand-worked positions.
#include "bowg/detection/odometry_gate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

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

// An entry facing `degrees` from the x axis (about z), `odometer` metres
// along, in run `run`.
DatabaseEntry facing(double degrees, double odometer, std::uint32_t run = 0) {
  DatabaseEntry e;
  e.heading.x = static_cast<float>(std::cos(degrees * M_PI / 180.0));
  e.heading.y = static_cast<float>(std::sin(degrees * M_PI / 180.0));
  e.heading.z = 0.f;
  e.odometer = odometer;
  e.odometry_run = run;
  return e;
}

IslandOptions headingGate(double base_deg, double drift_deg) {
  IslandOptions o;
  o.heading_gate_deg = base_deg;
  o.heading_gate_drift_deg = drift_deg;
  return o;
}

TEST(HeadingGate, BoundGrowsWithTheRootOfTheMetresDriven) {
  // 30 + 1.5 * sqrt(16) = 36 degrees, either order; 30 at the same odometer.
  EXPECT_DOUBLE_EQ(headingGateBound(headingGate(30, 1.5), 16.0), 36.0);
  EXPECT_DOUBLE_EQ(headingGateBound(headingGate(30, 1.5), -16.0), 36.0);
  EXPECT_DOUBLE_EQ(headingGateBound(headingGate(30, 1.5), 0.0), 30.0);
  EXPECT_DOUBLE_EQ(headingGateBound(headingGate(20, 0.0), 400.0), 20.0);
}

TEST(HeadingGate, EntriesTheRobotFacedAnotherWayAtAreRefused) {
  const IslandOptions o = headingGate(30, 1.5);
  const DatabaseEntry query = facing(0, 30.0);
  // 16 m driven apart: 36 degrees. 35 passes, 37 does not, either side.
  EXPECT_TRUE(withinHeadingGate(query, facing(35, 14.0), o));
  EXPECT_TRUE(withinHeadingGate(query, facing(-35, 14.0), o));
  EXPECT_FALSE(withinHeadingGate(query, facing(37, 14.0), o));
  // The robot turning into a junction's cross pipe a step after the
  // straight pass: 0.25 m driven, bound 30 + 1.5 * 0.5 = 30.75; the cross
  // pipe is 80 degrees away.
  EXPECT_FALSE(withinHeadingGate(query, facing(80, 29.75), o));
  EXPECT_TRUE(withinHeadingGate(query, facing(30.5, 29.75), o));
  // Driving the pipe the other way: 180 degrees.
  EXPECT_FALSE(withinHeadingGate(query, facing(180, 14.0), o));
}

TEST(HeadingGate, WithoutComparableHeadingsEverythingPasses) {
  const DatabaseEntry query = facing(0, 30.0);
  const DatabaseEntry across = facing(90, 29.0);
  EXPECT_FALSE(withinHeadingGate(query, across, headingGate(30, 1.5)));
  EXPECT_TRUE(withinHeadingGate(query, across, headingGate(0, 1.5)));  // gate off
  DatabaseEntry unknown = across;
  unknown.heading = OdometryHeading();
  EXPECT_TRUE(withinHeadingGate(query, unknown, headingGate(30, 1.5)));
  EXPECT_TRUE(withinHeadingGate(unknown, query, headingGate(30, 1.5)));
  // Another odometry run: another frame, headings not comparable.
  EXPECT_TRUE(withinHeadingGate(query, facing(90, 29.0, 1), headingGate(30, 1.5)));
  // Headings without odometers: no metres driven to scale the drift.
  DatabaseEntry no_odometer = across;
  no_odometer.odometer = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(withinHeadingGate(query, no_odometer, headingGate(30, 1.5)));
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
  EXPECT_TRUE(withinOdometryGate(query, far, gate(0.0, 0.1)));              // gate off
  EXPECT_TRUE(withinOdometryGate(query, DatabaseEntry(), gate(0.5, 0.1)));  // unknown position
  EXPECT_TRUE(withinOdometryGate(DatabaseEntry(), far, gate(0.5, 0.1)));
  // Another odometry run: another frame, positions not comparable.
  EXPECT_TRUE(withinOdometryGate(query, at(100, 0, 0, 29.0, 1), gate(0.5, 0.1)));
  // Positions without odometers: no metres driven to scale the drift.
  DatabaseEntry no_odometer = far;
  no_odometer.odometer = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(withinOdometryGate(query, no_odometer, gate(0.5, 0.1)));
}

// The gate judges a pair, near or far, only when it is on and both have a
// position and an odometer of the query's odometry run.
TEST(OdometryGate, AppliesOnlyToEntriesPlacedInTheQuerysRun) {
  const DatabaseEntry query = at(0, 0, 0, 30.0);
  EXPECT_TRUE(odometryGateApplies(query, at(100, 0, 0, 29.0), gate(0.5, 0.1)));
  EXPECT_TRUE(odometryGateApplies(query, at(0.1, 0, 0, 29.9), gate(0.5, 0.1)));
  EXPECT_FALSE(odometryGateApplies(query, at(0.1, 0, 0, 29.9), gate(0.0, 0.1)));  // off
  EXPECT_FALSE(odometryGateApplies(query, DatabaseEntry(), gate(0.5, 0.1)));
  EXPECT_FALSE(odometryGateApplies(DatabaseEntry(), query, gate(0.5, 0.1)));
  EXPECT_FALSE(odometryGateApplies(query, at(0.1, 0, 0, 29.9, 1), gate(0.5, 0.1)));
  DatabaseEntry no_odometer = at(0.1, 0, 0, 29.9);
  no_odometer.odometer = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(odometryGateApplies(query, no_odometer, gate(0.5, 0.1)));
}

IslandOptions anchor(double anchor_m, double drift) {
  IslandOptions o;
  o.odometry_anchor_m = anchor_m;
  o.odometry_gate_drift = drift;
  return o;
}

// One accepted loop as the gate's anchors.
std::vector<AnchorEntries> loop(const DatabaseEntry& query, const DatabaseEntry& match) {
  return {{&query, &match}};
}

TEST(LoopAnchor, RadiusGrowsWithTheMetresDrivenOnBothSides) {
  EXPECT_DOUBLE_EQ(loopAnchorRadius(anchor(0.3, 0.05), 0.0, 0.0), 0.3);
  // 2 m since the anchor's query, 14 m (a lap) from its match: 0.3 + 0.8.
  EXPECT_DOUBLE_EQ(loopAnchorRadius(anchor(0.3, 0.05), 2.0, -14.0), 1.1);
  EXPECT_DOUBLE_EQ(loopAnchorRadius(anchor(0.3, 0.0), 50.0, 50.0), 0.3);
}

TEST(LoopAnchor, TheEntryMustHaveMovedFromTheMatchAsTheQueryFromItsLoop) {
  const IslandOptions o = anchor(0.3, 0.05);
  // The last loop: the robot at (30, 1, 0) (odometer 60) was at the place of
  // the entry at (29.6, 0, 0) (odometer 29.6): the odometry drifted 0.4 m
  // in x and 1 m in y in 30 m. The query drove 1.0 m on to (31, 1, 0).
  const DatabaseEntry q0 = at(30, 1, 0, 60.0);
  const DatabaseEntry m0 = at(29.6, 0, 0, 29.6);
  const DatabaseEntry q = at(31, 1, 0, 61.0);
  // (30.6, 0, 0): moved 1.0 m from m0 as the query from q0: 0 m off.
  EXPECT_TRUE(withinLoopAnchors(q, at(30.6, 0, 0, 30.6), loop(q0, m0), o));
  // A look-alike 0.5 m further, (31.1, 0, 0): 0.5 m off; radius 0.3 +
  // 0.05 * (1.0 + 1.5) = 0.425 m. Yet the absolute gate, 1 + 0.05 * 30.4,
  // would let it through (1.005 m away).
  EXPECT_FALSE(withinLoopAnchors(q, at(31.1, 0, 0, 31.1), loop(q0, m0), o));
  EXPECT_TRUE(withinOdometryGate(q, at(31.1, 0, 0, 31.1), gate(1.0, 0.05)));
  // 0.4 m off sideways after 1.0 m along: (31.0, 0.4, 0) is sqrt(0.4^2 +
  // 0.4^2) = 0.566 m off, radius 0.3 + 0.05 * (1.0 + 1.4) = 0.42: outside;
  // (30.9, 0.2, 0): sqrt(0.3^2 + 0.2^2) = 0.361 m off, radius 0.415: inside.
  EXPECT_FALSE(withinLoopAnchors(q, at(31.0, 0.4, 0, 31.0), loop(q0, m0), o));
  EXPECT_TRUE(withinLoopAnchors(q, at(30.9, 0.2, 0, 30.9), loop(q0, m0), o));
  // Boundary, without drift allowance (radius 0.25 m) and with an anchor
  // match at (29.5, 0, 0): (30.75, 0, 0) moved 1.25 m, exactly 0.25 m off:
  // inside; (30.8, 0, 0) is 0.3 m off: outside.
  const DatabaseEntry m1 = at(29.5, 0, 0, 29.5);
  EXPECT_TRUE(withinLoopAnchors(q, at(30.75, 0, 0, 30.75), loop(q0, m1), anchor(0.25, 0.0)));
  EXPECT_FALSE(withinLoopAnchors(q, at(30.8, 0, 0, 30.8), loop(q0, m1), anchor(0.25, 0.0)));
}

TEST(LoopAnchor, WithoutComparablePositionsEverythingPasses) {
  const DatabaseEntry q0 = at(30, 1, 0, 60.0);
  const DatabaseEntry m0 = at(29.6, 0, 0, 29.6);
  const DatabaseEntry q = at(31, 1, 0, 61.0);
  const DatabaseEntry far = at(80, 0, 0, 80.0);
  EXPECT_FALSE(withinLoopAnchors(q, far, loop(q0, m0), anchor(0.3, 0.05)));
  EXPECT_TRUE(withinLoopAnchors(q, far, loop(q0, m0), anchor(0.0, 0.05)));  // off
  EXPECT_TRUE(withinLoopAnchors(q, DatabaseEntry(), loop(q0, m0), anchor(0.3, 0.05)));
  EXPECT_TRUE(withinLoopAnchors(q, far, loop(DatabaseEntry(), m0), anchor(0.3, 0.05)));
  EXPECT_TRUE(withinLoopAnchors(q, far, loop(q0, DatabaseEntry()), anchor(0.3, 0.05)));
  // An anchor of another odometry run (a loaded detector's old loop).
  EXPECT_TRUE(withinLoopAnchors(q, far, loop(q0, at(29.6, 0, 0, 29.6, 1)), anchor(0.3, 0.05)));
  EXPECT_TRUE(withinLoopAnchors(q, at(80, 0, 0, 80.0, 1), loop(q0, m0), anchor(0.3, 0.05)));
}

// A circuit of 15 m laps along x; each lap's odometry 0.3 m further off in
// y. The query is on lap 3 at x = 1.0 (odometer 46). Two recent loops: A
// (the last) from x = 0.5 to lap 2, B from x = 0 to lap 1.
TEST(LoopAnchor, EachEntryIsJudgedByTheAnchorOnItsOwnLap) {
  const IslandOptions o = anchor(0.3, 0.05);
  const DatabaseEntry q = at(1.0, 0.9, 0, 46.0);
  const DatabaseEntry a_query = at(0.5, 0.9, 0, 45.5), a_match = at(0.5, 0.6, 0, 30.5);
  const DatabaseEntry b_query = at(0.0, 0.9, 0, 45.0), b_match = at(0.0, 0.3, 0, 15.0);
  const std::vector<AnchorEntries> a{{&a_query, &a_match}};
  const std::vector<AnchorEntries> ab{{&a_query, &a_match}, {&b_query, &b_match}};
  // The true place on lap 1 (x = 1.0, odometer 16): by B, radius 0.3 + 0.05
  // * (1.0 + 1.0) = 0.4 (A's would be 0.3 + 0.05 * (0.5 + 14.5) = 1.05):
  // it moved 1.0 m from B's match as the query from B's query: 0 m off.
  const DatabaseEntry place = at(1.0, 0.3, 0, 16.0);
  EXPECT_TRUE(withinLoopAnchors(q, place, ab, o));
  // A look-alike 0.5 m further on lap 1: by B 0.5 m off, radius 0.425:
  // outside. A alone, a lap from it, has radius 0.3 + 0.05 * (0.5 + 14) =
  // 1.025 and finds it sqrt(0.5^2 + 0.3^2) = 0.583 m off: inside.
  const DatabaseEntry look_alike = at(1.5, 0.3, 0, 16.5);
  EXPECT_TRUE(withinLoopAnchors(q, look_alike, a, o));
  EXPECT_FALSE(withinLoopAnchors(q, look_alike, ab, o));
  // Without anchors, with the gate off, or with anchors of another run:
  // nothing is gated.
  EXPECT_TRUE(withinLoopAnchors(q, look_alike, {}, o));
  EXPECT_TRUE(withinLoopAnchors(q, look_alike, ab, anchor(0.0, 0.05)));
  const DatabaseEntry old_match = at(0.0, 0.3, 0, 15.0, 1);
  EXPECT_TRUE(withinLoopAnchors(q, look_alike, {{&a_query, &a_match}, {&b_query, &old_match}}, o));
}

// anchoredByRecentLoop: the anchor's radius must be at most twice
// odometry_anchor_m. With 0.25 m and 0.0625 per metre (exact in binary):
// 0.25 + 0.0625 * (driven since the loop on both sides) <= 0.5 up to 4 m
// of driving together.
TEST(LoopAnchor, OnlyARecentLoopAnchorsThePlace) {
  const IslandOptions o = anchor(0.25, 0.0625);
  const DatabaseEntry m0 = at(10.0, 0, 0, 10.0);
  const DatabaseEntry q0 = at(30.0, 0.25, 0, 60.0);
  // 1 m on both passes since the loop: radius 0.375, 0 m off.
  const DatabaseEntry q = at(31.0, 0.25, 0, 61.0);
  const std::vector<AnchorEntries> recent{{&q0, &m0}};
  EXPECT_TRUE(anchoredByRecentLoop(q, at(11.0, 0, 0, 11.0), recent, o));
  // 0.5 m off the anchored place: outside its radius 0.25 + 0.0625 * 2.5.
  EXPECT_FALSE(anchoredByRecentLoop(q, at(11.5, 0, 0, 11.5), recent, o));
  // 2 m on both: radius 0.5, the limit: anchored. 2.5 m on both (radius
  // 0.5625): within the anchor's radius, but not anchored.
  EXPECT_TRUE(anchoredByRecentLoop(at(32.0, 0.25, 0, 62.0), at(12.0, 0, 0, 12.0), recent, o));
  const DatabaseEntry q25 = at(32.5, 0.25, 0, 62.5), e25 = at(12.5, 0, 0, 12.5);
  EXPECT_TRUE(withinLoopAnchors(q25, e25, recent, o));
  EXPECT_FALSE(anchoredByRecentLoop(q25, e25, recent, o));
  // No anchor, or the gate off: nothing is anchored.
  EXPECT_FALSE(anchoredByRecentLoop(q, at(11.0, 0, 0, 11.0), {}, o));
  EXPECT_FALSE(anchoredByRecentLoop(q, at(11.0, 0, 0, 11.0), recent, anchor(0.0, 0.0625)));
}

// A loop from run 1 (the live mission) into run 0 (an earlier one, whose
// frame is turned and moved): q0 = (0, 0, 0) odometer 10 was at the place of
// m0 = (5, 5, 0) odometer 40. The query drove 1 m to (1, 0, 0). An entry of
// run 0 must lie as far from m0 as the query from q0 (1 m), within 0.3 +
// 0.05 * (1 + |driven m0..e|).
TEST(CrossRunAnchor, TheEntryMustLieAsFarFromTheMatchAsTheQueryFromItsLoop) {
  const IslandOptions o = anchor(0.3, 0.05);
  const DatabaseEntry q0 = at(0, 0, 0, 10.0, 1), m0 = at(5, 5, 0, 40.0, 0);
  const DatabaseEntry q = at(1, 0, 0, 11.0, 1);
  // (5, 6, 0), 1 m from m0: 0 m off (radius 0.4), whatever the direction
  // (the frames' rotation is unknown): (4, 5, 0) too.
  EXPECT_TRUE(withinCrossRunAnchors(q, at(5, 6, 0, 41.0, 0), loop(q0, m0), o));
  EXPECT_TRUE(withinCrossRunAnchors(q, at(4, 5, 0, 39.0, 0), loop(q0, m0), o));
  // A look-alike 5 m on, (8, 9, 0): 4 m off, radius 0.3 + 0.05 * 6 = 0.6.
  EXPECT_FALSE(withinCrossRunAnchors(q, at(8, 9, 0, 45.0, 0), loop(q0, m0), o));
  // (5, 6.5, 0): 0.5 m off, radius 0.3 + 0.05 * 2.5 = 0.425: outside;
  // (5, 6.4, 0): 0.4 m off, radius 0.42: inside.
  EXPECT_FALSE(withinCrossRunAnchors(q, at(5, 6.5, 0, 41.5, 0), loop(q0, m0), o));
  EXPECT_TRUE(withinCrossRunAnchors(q, at(5, 6.4, 0, 41.4, 0), loop(q0, m0), o));
  // The loop-anchored gate of one run says nothing here.
  EXPECT_TRUE(withinLoopAnchors(q, at(8, 9, 0, 45.0, 0), loop(q0, m0), o));
}

// Without positions (an odometer alone) the gate does not apply: metres
// driven from the anchor's match say nothing once the two surveys part at a
// junction (the earlier one may have taken the other pipe).
TEST(CrossRunAnchor, AnOdometerAloneIsNotEnough) {
  const IslandOptions o = anchor(0.3, 0.05);
  DatabaseEntry q0, m0, q, e;
  q0.odometer = 10.0;
  q0.odometry_run = 1;
  q = q0;
  q.odometer = 12.0;
  m0.odometer = 40.0;
  e = m0;
  e.odometer = 45.0;  // 5 m from m0 after 2 m: the ring would refuse it
  EXPECT_TRUE(withinCrossRunAnchors(q, e, loop(q0, m0), o));
}

TEST(CrossRunAnchor, WithoutAnAnchorIntoTheEntrysRunEverythingPasses) {
  const IslandOptions o = anchor(0.3, 0.05);
  const DatabaseEntry q0 = at(0, 0, 0, 10.0, 1), m0 = at(5, 5, 0, 40.0, 0);
  const DatabaseEntry q = at(1, 0, 0, 11.0, 1), far = at(8, 9, 0, 45.0, 0);
  EXPECT_TRUE(withinCrossRunAnchors(q, far, {}, o));                             // no loop
  EXPECT_TRUE(withinCrossRunAnchors(q, far, loop(q0, m0), anchor(0, 0.05)));     // gate off
  EXPECT_TRUE(withinCrossRunAnchors(q, at(8, 9, 0, 45.0, 2), loop(q0, m0), o));  // run 2
  EXPECT_TRUE(withinCrossRunAnchors(q, at(8, 9, 0, 15.0, 1), loop(q0, m0), o));  // own run
  DatabaseEntry no_odometer = far;
  no_odometer.odometer = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(withinCrossRunAnchors(q, no_odometer, loop(q0, m0), o));
}

// The metric translation's bound: what the gates assume of the odometry.
TEST(OdometryDistanceBound, TheGatesDistancePlusTheirRadius) {
  const double inf = std::numeric_limits<double>::infinity();
  const DatabaseEntry query = at(0, 0, 0, 30.0);
  // Absolute gate: (3, 4, 0) is 5 m away, 20 m driven apart: radius 0.5 +
  // 0.1 * 20 = 2.5 m, bound 7.5 m.
  EXPECT_DOUBLE_EQ(odometryDistanceBound(query, at(3, 4, 0, 10.0), {}, gate(0.5, 0.1)), 7.5);
  // Gate off, or positions not comparable: no bound.
  EXPECT_EQ(odometryDistanceBound(query, at(3, 4, 0, 10.0), {}, gate(0.0, 0.1)), inf);
  EXPECT_EQ(odometryDistanceBound(query, DatabaseEntry(), {}, gate(0.5, 0.1)), inf);
  EXPECT_EQ(odometryDistanceBound(query, at(3, 4, 0, 10.0, 1), {}, gate(0.5, 0.1)), inf);

  // The loop of LoopAnchor above: q0 (30, 1, 0) at m0 (29.6, 0, 0); the
  // query (31, 1, 0) drove 1.0 m on. The entry (30.9, 0.2, 0) is sqrt(0.3^2
  // + 0.2^2) = 0.3606 m off the anchor's prediction (30.6, 0, 0); radius
  // 0.3 + 0.05 * (1.0 + 1.3) = 0.415 m: bound 0.7756 m.
  const DatabaseEntry q0 = at(30, 1, 0, 60.0);
  const DatabaseEntry m0 = at(29.6, 0, 0, 29.6);
  const DatabaseEntry q = at(31, 1, 0, 61.0);
  const DatabaseEntry e = at(30.9, 0.2, 0, 30.9);
  const double anchored = std::sqrt(0.13) + 0.415;
  EXPECT_NEAR(odometryDistanceBound(q, e, loop(q0, m0), anchor(0.3, 0.05)), anchored, 1e-12);
  // With the absolute gate on too, the smaller: the entry is sqrt(0.1^2 +
  // 0.8^2) = 0.806 m from the query, 30.1 m driven apart: 0.806 + 1 + 0.05 *
  // 30.1 = 3.31 m; the anchor's 0.776 m wins.
  IslandOptions both = anchor(0.3, 0.05);
  both.odometry_gate_m = 1.0;
  EXPECT_NEAR(odometryDistanceBound(q, e, loop(q0, m0), both), anchored, 1e-12);
  // Without an anchor, the absolute gate's.
  EXPECT_NEAR(odometryDistanceBound(q, e, {}, both), std::sqrt(0.65) + 1.0 + 0.05 * 30.1, 1e-12);
  // An anchor of another odometry run does not apply.
  const DatabaseEntry other = at(29.6, 0, 0, 29.6, 1);
  EXPECT_EQ(odometryDistanceBound(q, e, loop(q0, other), anchor(0.3, 0.05)), inf);
}

}  // namespace
}  // namespace bowg
