// KeyframeGate: time interval, travelled distance, stamp order.
#include "bowg_ros/keyframe_gate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace bowg_ros {
namespace {

TEST(KeyframeGate, EveryIncreasingFrameIsAKeyframeByDefault) {
  KeyframeGate gate;
  EXPECT_EQ(gate.check(1.0), GateDecision::kAccept);
  EXPECT_EQ(gate.check(1.001), GateDecision::kAccept);
  EXPECT_EQ(gate.check(2.0), GateDecision::kAccept);
}

TEST(KeyframeGate, MinimumIntervalCountsFromTheLastKeyframe) {
  KeyframeGateOptions o;
  o.min_interval = 0.5;
  KeyframeGate gate(o);
  EXPECT_EQ(gate.check(10.0), GateDecision::kAccept);   // first frame
  EXPECT_EQ(gate.check(10.2), GateDecision::kTooSoon);  // 0.2 < 0.5
  EXPECT_EQ(gate.check(10.4), GateDecision::kTooSoon);  // 0.4 < 0.5 (from 10.0, not 10.2)
  EXPECT_EQ(gate.check(10.5), GateDecision::kAccept);   // 0.5 >= 0.5
  EXPECT_EQ(gate.check(10.9), GateDecision::kTooSoon);  // 0.4 from 10.5
  EXPECT_EQ(gate.check(11.0), GateDecision::kAccept);
}

TEST(KeyframeGate, AFrameWithinTenPercentOfTheIntervalIsOnTime) {
  // A 10 Hz camera under a 0.1 s gate (0.04 m at 0.4 m/s): stamps a few ms
  // early, or 0.1 apart only up to rounding, keep every frame.
  KeyframeGateOptions o;
  o.min_interval = 0.1;
  KeyframeGate camera(o);
  const double stamps[] = {1000.0, 1000.1, 1000.197, 1000.3, 1000.4, 1000.492};
  for (double t : stamps) EXPECT_EQ(camera.check(t), GateDecision::kAccept) << t;
  // The tolerance is 10 % of the interval, no more: 0.46 of 0.5 is on time,
  // 0.44 is not.
  o.min_interval = 0.5;
  KeyframeGate slow(o);
  EXPECT_EQ(slow.check(10.0), GateDecision::kAccept);
  EXPECT_EQ(slow.check(10.44), GateDecision::kTooSoon);
  EXPECT_EQ(slow.check(10.46), GateDecision::kAccept);
}

TEST(KeyframeGate, OutOfOrderAndRepeatedStampsAreRejected) {
  KeyframeGate gate;
  EXPECT_EQ(gate.check(5.0), GateDecision::kAccept);
  EXPECT_EQ(gate.check(5.0), GateDecision::kRepeatedStamp);
  EXPECT_EQ(gate.check(4.0), GateDecision::kOutOfOrder);
  EXPECT_EQ(gate.check(6.0), GateDecision::kAccept);
  // Judged against the previous frame even when that one was not a keyframe.
  KeyframeGateOptions o;
  o.min_interval = 1.0;
  KeyframeGate slow(o);
  EXPECT_EQ(slow.check(1.0), GateDecision::kAccept);
  EXPECT_EQ(slow.check(1.5), GateDecision::kTooSoon);
  EXPECT_EQ(slow.check(1.2), GateDecision::kOutOfOrder);
}

TEST(KeyframeGate, TravelledDistanceIsThePathLengthSinceTheLastKeyframe) {
  KeyframeGateOptions o;
  o.min_distance = 1.0;
  KeyframeGate gate(o);
  // No odometry yet: only the time gate applies.
  EXPECT_EQ(gate.check(1.0), GateDecision::kAccept);
  EXPECT_EQ(gate.check(2.0), GateDecision::kAccept);
  gate.addPosition(0, 0, 0);
  gate.addPosition(0.3, 0.4, 0);  // 0.5 m (3-4-5 triangle)
  EXPECT_TRUE(gate.hasOdometry());
  EXPECT_NEAR(gate.travelledSinceKeyframe(), 0.5, 1e-12);
  EXPECT_EQ(gate.check(3.0), GateDecision::kTooClose);
  gate.addPosition(0.3, 0.4, 0.6);  // + 0.6 m = 1.1 m of path
  EXPECT_NEAR(gate.travelledSinceKeyframe(), 1.1, 1e-12);
  EXPECT_EQ(gate.check(4.0), GateDecision::kAccept);
  EXPECT_EQ(gate.travelledSinceKeyframe(), 0.0);
  // Back and forth counts as path, not displacement: 0.6 + 0.6 = 1.2 m.
  gate.addPosition(0.3, 0.4, 0.0);
  gate.addPosition(0.3, 0.4, 0.6);
  EXPECT_NEAR(gate.travelledSinceKeyframe(), 1.2, 1e-12);
  EXPECT_EQ(gate.check(5.0), GateDecision::kAccept);
  // Non-finite positions are ignored.
  gate.addPosition(NAN, 0, 0);
  EXPECT_EQ(gate.travelledSinceKeyframe(), 0.0);
}

TEST(KeyframeGate, TimeAndDistanceMustBothPass) {
  KeyframeGateOptions o;
  o.min_interval = 1.0;
  o.min_distance = 1.0;
  KeyframeGate gate(o);
  gate.addPosition(0, 0, 0);
  EXPECT_EQ(gate.check(0.0), GateDecision::kAccept);
  gate.addPosition(2, 0, 0);
  EXPECT_EQ(gate.check(0.5), GateDecision::kTooSoon);  // far enough, too soon
  EXPECT_EQ(gate.check(1.0), GateDecision::kAccept);
  EXPECT_EQ(gate.check(2.5), GateDecision::kTooClose);  // late enough, not far enough
}

TEST(KeyframeGate, PositionIsTheLastFiniteOdometryPosition) {
  KeyframeGate gate;
  EXPECT_TRUE(gate.position().unknown());  // no odometry yet
  gate.addPosition(1.5, -2, 0.25);
  gate.addPosition(NAN, 7, 7);  // ignored
  const bowg::OdometryPosition p = gate.position();
  EXPECT_EQ(p.x, 1.5);
  EXPECT_EQ(p.y, -2.0);
  EXPECT_EQ(p.z, 0.25);
}

TEST(KeyframeGate, ResetForgetsFramesAndPositions) {
  KeyframeGate gate;
  gate.addPosition(0, 0, 0);
  EXPECT_EQ(gate.check(10.0), GateDecision::kAccept);
  gate.reset();
  EXPECT_FALSE(gate.hasOdometry());
  EXPECT_TRUE(gate.position().unknown());
  EXPECT_EQ(gate.check(1.0), GateDecision::kAccept);  // older stamp accepted after a reset
}

TEST(KeyframeGate, OdometerIsThePathLengthSinceTheStartAcrossKeyframes) {
  KeyframeGate gate;
  EXPECT_TRUE(std::isnan(gate.odometer()));  // no odometry yet
  gate.addPosition(0, 0, 0);
  EXPECT_DOUBLE_EQ(gate.odometer(), 0.0);
  gate.addPosition(3, 4, 0);  // 5 m
  EXPECT_EQ(gate.check(1.0), GateDecision::kAccept);
  gate.addPosition(3, 4, 2);  // 2 m more; a keyframe does not restart it
  EXPECT_DOUBLE_EQ(gate.odometer(), 7.0);
  EXPECT_DOUBLE_EQ(gate.travelledSinceKeyframe(), 2.0);
  gate.addPosition(3, 4, 1);  // backing up counts too: metres driven
  EXPECT_DOUBLE_EQ(gate.odometer(), 8.0);
  // After loading a database driven up to 120 m the odometer continues.
  gate.reset();
  EXPECT_TRUE(std::isnan(gate.odometer()));
  gate.setOdometer(120.0);
  gate.addPosition(0, 0, 0);
  gate.addPosition(0, 0.5, 0);
  EXPECT_DOUBLE_EQ(gate.odometer(), 120.5);
  EXPECT_THROW(gate.setOdometer(-1.0), std::invalid_argument);
}

// A robot without positions: a cable counter's readings give the odometer
// and the distance gate, no position; positions take over once they come.
TEST(KeyframeGate, OdometerReadingsGiveThePathWithoutAPosition) {
  KeyframeGateOptions o;
  o.min_distance = 0.5;
  KeyframeGate gate(o);
  EXPECT_TRUE(gate.addOdometerReading(10.0));  // any origin: the first reading is 0 m driven
  EXPECT_TRUE(gate.hasOdometry());
  EXPECT_FALSE(gate.hasPositions());
  EXPECT_DOUBLE_EQ(gate.odometer(), 0.0);
  EXPECT_TRUE(gate.position().unknown());
  EXPECT_EQ(gate.check(1.0), GateDecision::kAccept);
  EXPECT_TRUE(gate.addOdometerReading(10.25));
  EXPECT_EQ(gate.check(2.0), GateDecision::kTooClose);  // 0.25 m of 0.5
  EXPECT_TRUE(gate.addOdometerReading(10.0));           // reeled in 0.25 m: driven too
  EXPECT_DOUBLE_EQ(gate.odometer(), 0.5);
  EXPECT_EQ(gate.check(3.0), GateDecision::kAccept);
  EXPECT_FALSE(gate.addOdometerReading(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_DOUBLE_EQ(gate.odometer(), 0.5);
  // Positions arrive: they measure the path from now on, readings are ignored.
  gate.addPosition(0, 0, 0);
  EXPECT_TRUE(gate.hasPositions());
  EXPECT_FALSE(gate.addOdometerReading(20.0));
  gate.addPosition(0, 0.75, 0);
  EXPECT_DOUBLE_EQ(gate.odometer(), 1.25);
  // A reset forgets the readings.
  gate.reset();
  EXPECT_FALSE(gate.hasOdometry());
  EXPECT_TRUE(gate.addOdometerReading(3.0));
  EXPECT_DOUBLE_EQ(gate.odometer(), 0.0);
}

TEST(KeyframeGate, AReadingOfEitherSourceGoesWhereItsSourceGoes) {
  KeyframeGate gate;
  EXPECT_TRUE(gate.addReading(OdometryReading::odometer(4.0)));
  EXPECT_TRUE(gate.addReading(OdometryReading::odometer(4.5)));  // 0.5 m driven
  EXPECT_FALSE(gate.hasPositions());
  EXPECT_DOUBLE_EQ(gate.odometer(), 0.5);
  EXPECT_TRUE(gate.addReading(OdometryReading::position(1.0, 2.0, 2.0)));
  EXPECT_TRUE(gate.addReading(OdometryReading::position(1.0, 5.0, 6.0)));  // 3-4-5: 5 m
  EXPECT_DOUBLE_EQ(gate.odometer(), 5.5);
  EXPECT_DOUBLE_EQ(gate.position().x, 1.0);
  EXPECT_DOUBLE_EQ(gate.position().z, 6.0);
  EXPECT_FALSE(gate.addReading(OdometryReading::odometer(9.0)));  // positions won
  EXPECT_DOUBLE_EQ(gate.odometer(), 5.5);
}

TEST(KeyframeGate, APositionsHeadingIsTheKeyframesUntilTheNextPosition) {
  KeyframeGate gate;
  EXPECT_TRUE(gate.heading().unknown());
  bowg::OdometryHeading east;
  east.x = 1.f, east.y = 0.f, east.z = 0.f;
  gate.addReading(OdometryReading::position(1.0, 2.0, 3.0, east));
  EXPECT_EQ(gate.heading().x, 1.f);
  // A non-finite position is ignored with its heading; a position without a
  // heading makes it unknown; odometer readings leave it.
  gate.addReading(OdometryReading::position(std::nan(""), 0.0, 0.0));
  EXPECT_EQ(gate.heading().x, 1.f);
  gate.addReading(OdometryReading::odometer(3.0));
  EXPECT_EQ(gate.heading().x, 1.f);
  gate.addReading(OdometryReading::position(1.0, 2.0, 4.0));
  EXPECT_TRUE(gate.heading().unknown());
  gate.addReading(OdometryReading::position(1.0, 2.0, 5.0, east));
  gate.reset();
  EXPECT_TRUE(gate.heading().unknown());
}

TEST(KeyframeGate, StampFloorRejectsFramesUpToALoadedDatabasesLastKeyframe) {
  KeyframeGate gate;
  gate.setStampFloor(100.0);
  EXPECT_EQ(gate.check(50.0), GateDecision::kBeforeFloor);
  EXPECT_EQ(gate.check(100.0), GateDecision::kBeforeFloor);  // equal is not after
  EXPECT_EQ(gate.check(100.5), GateDecision::kAccept);
  EXPECT_TRUE(isStampRejection(GateDecision::kBeforeFloor));
  gate.reset();  // a database reset lifts the floor
  EXPECT_EQ(gate.check(1.0), GateDecision::kAccept);
}

TEST(KeyframeGate, AJumpBackBeyondTheResetThresholdStartsANewRun) {
  KeyframeGateOptions o;
  o.min_interval = 1.0;
  o.time_jump_reset = 5.0;
  KeyframeGate gate(o);
  gate.addPosition(0, 0, 0);
  gate.addPosition(10, 0, 0);
  EXPECT_EQ(gate.check(100.0), GateDecision::kAccept);
  EXPECT_EQ(gate.check(101.0), GateDecision::kAccept);
  EXPECT_EQ(gate.check(97.0), GateDecision::kOutOfOrder);  // 4 s back: not more than 5
  EXPECT_EQ(gate.epoch(), 0u);
  // The bag starts over: 101 -> 95 is 6 s back.
  EXPECT_EQ(gate.check(95.0), GateDecision::kTimeJump);
  EXPECT_TRUE(isKeyframe(GateDecision::kTimeJump));
  EXPECT_EQ(gate.epoch(), 1u);
  EXPECT_FALSE(gate.hasOdometry());  // positions of the old run forgotten
  // The jump frame is the new run's first keyframe: the interval counts from it.
  EXPECT_EQ(gate.check(95.5), GateDecision::kTooSoon);
  EXPECT_EQ(gate.check(96.0), GateDecision::kAccept);
  gate.reset();  // the epoch survives a reset
  EXPECT_EQ(gate.epoch(), 1u);
  // Off (0): a jump back of any size is only out of order.
  KeyframeGate off;
  EXPECT_EQ(off.check(1000.0), GateDecision::kAccept);
  EXPECT_EQ(off.check(1.0), GateDecision::kOutOfOrder);
  EXPECT_EQ(off.epoch(), 0u);
}

TEST(KeyframeGate, ATimeJumpIsMoreThanTheResetBackFromThePreviousStamp) {
  EXPECT_TRUE(isTimeJump(94.9, 100.0, 5.0));   // 5.1 s back
  EXPECT_FALSE(isTimeJump(95.0, 100.0, 5.0));  // exactly 5: not more
  EXPECT_FALSE(isTimeJump(99.0, 100.0, 5.0));  // out of order only
  EXPECT_FALSE(isTimeJump(101.0, 100.0, 5.0));
  EXPECT_FALSE(isTimeJump(0.0, 1000.0, 0.0));  // 0: never
}

TEST(KeyframeGate, RejectsInvalidOptions) {
  KeyframeGateOptions o;
  o.min_interval = -1.0;
  EXPECT_THROW(KeyframeGate{o}, std::invalid_argument);
  o.min_interval = 0.0;
  o.min_distance = NAN;
  EXPECT_THROW(KeyframeGate{o}, std::invalid_argument);
  o.min_distance = 0.0;
  o.time_jump_reset = -1.0;
  EXPECT_THROW(KeyframeGate{o}, std::invalid_argument);
}

}  // namespace
}  // namespace bowg_ros
