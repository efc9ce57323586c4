// OdometryMerge: a frame gets the readings stamped up to it, whichever
// arrived first, from every source that sends them; late and overflowing
// frames go on, marked late.
#include "bowg_ros/odometry_merge.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace bowg_ros {
namespace {

// What the merge handed on, in order: "r<metres>" for an odometer reading,
// "p<x>" for a position, "f<id>" for a frame on time, "L<id>" for a late one.
struct Log {
  std::vector<std::string> events;
  void release(OdometryMerge<int>* merge, double now, double wait) {
    merge->release(
        now, wait,
        [this](const OdometryReading& r) {
          events.push_back(r.source == OdometryReading::kOdometer
                               ? "r" + std::to_string(int(r.metres))
                               : "p" + std::to_string(int(r.x)));
        },
        [this](int&& id, bool late) { events.push_back((late ? "L" : "f") + std::to_string(id)); });
  }
};

// An odometer reading of `metres` stamped `stamp`.
bool addMetres(OdometryMerge<int>* merge, double stamp, double metres) {
  return merge->addReading(stamp, OdometryReading::odometer(metres));
}
bool addPosition(OdometryMerge<int>* merge, double stamp, double x) {
  return merge->addReading(stamp, OdometryReading::position(x, 0.0, 0.0));
}

using Events = std::vector<std::string>;

TEST(OdometryMerge, AFrameWaitsForTheReadingAtItsStamp) {
  OdometryMerge<int> merge;
  Log log;
  // The image of t = 1.0 is handled before the reading stamped 1.0.
  ASSERT_TRUE(addMetres(&merge, 0.9, 9));
  merge.addFrame(1.0, /*arrival*/ 100.0, 1);
  log.release(&merge, 100.01, 0.2);
  // 0.9 < 1.0: the frame waits; the reading before it goes on.
  EXPECT_EQ(log.events, Events({"r9"}));
  ASSERT_TRUE(addMetres(&merge, 1.0, 10));
  log.release(&merge, 100.02, 0.2);
  EXPECT_EQ(log.events, Events({"r9", "r10", "f1"}));
  EXPECT_EQ(merge.waiting(), 0u);
}

TEST(OdometryMerge, ReadingsAfterAFrameStayAfterIt) {
  OdometryMerge<int> merge;
  Log log;
  merge.addFrame(1.0, 100.0, 1);
  merge.addFrame(2.0, 100.1, 2);
  // One reading past both frames arrives with two before it: each frame
  // gets exactly the readings stamped at or before it.
  ASSERT_TRUE(addMetres(&merge, 0.5, 5));
  ASSERT_TRUE(addMetres(&merge, 1.5, 15));
  ASSERT_TRUE(addMetres(&merge, 2.5, 25));
  log.release(&merge, 100.2, 0.2);
  EXPECT_EQ(log.events, Events({"r5", "f1", "r15", "f2", "r25"}));
}

TEST(OdometryMerge, WithNoFrameWaitingReadingsGoOnAtOnce) {
  OdometryMerge<int> merge;
  Log log;
  ASSERT_TRUE(addMetres(&merge, 3.0, 30));
  log.release(&merge, 0.0, 0.2);
  EXPECT_EQ(log.events, Events({"r30"}));
  // A frame the readings have passed goes on at once too.
  merge.addFrame(2.0, 0.0, 7);
  log.release(&merge, 0.0, 0.2);
  EXPECT_EQ(log.events, Events({"r30", "f7"}));
}

TEST(OdometryMerge, AFrameWhoseReadingNeverComesGoesOnLate) {
  OdometryMerge<int> merge;
  Log log;
  ASSERT_TRUE(addMetres(&merge, 0.9, 9));
  merge.addFrame(1.0, 100.0, 1);
  merge.addFrame(1.1, 100.1, 2);
  log.release(&merge, 100.19, 0.2);  // waited 0.19 s < 0.2
  EXPECT_EQ(log.events, Events({"r9"}));
  log.release(&merge, 100.2, 0.2);  // frame 1 waited 0.2 s: late; frame 2 0.1 s
  EXPECT_EQ(log.events, Events({"r9", "L1"}));
  log.release(&merge, 100.3, 0.2);
  EXPECT_EQ(log.events, Events({"r9", "L1", "L2"}));
}

TEST(OdometryMerge, BeyondItsBoundTheOldestFrameGoesOnLate) {
  OdometryMerge<int> merge(2);
  Log log;
  merge.addFrame(1.0, 0.0, 1);
  merge.addFrame(2.0, 0.0, 2);
  log.release(&merge, 0.0, 10.0);
  EXPECT_EQ(log.events, Events({}));
  merge.addFrame(3.0, 0.0, 3);
  log.release(&merge, 0.0, 10.0);
  EXPECT_EQ(log.events, Events({"L1"}));
  EXPECT_EQ(merge.waiting(), 2u);
}

TEST(OdometryMerge, AReadingStampedBeforeThePreviousIsDropped) {
  OdometryMerge<int> merge;
  Log log;
  ASSERT_TRUE(addMetres(&merge, 2.0, 20));
  EXPECT_FALSE(addMetres(&merge, 1.0, 10));
  EXPECT_TRUE(addMetres(&merge, 2.0, 21));  // the same stamp is not out of order
  log.release(&merge, 0.0, 0.2);
  EXPECT_EQ(log.events, Events({"r20", "r21"}));
}

TEST(OdometryMerge, ANewRunOfReadingsTakesEarlierStampsAndKeepsTheFrames) {
  OdometryMerge<int> merge;
  Log log;
  ASSERT_TRUE(addMetres(&merge, 50.0, 50));
  merge.addFrame(1.0, 0.0, 1);  // a frame of the new run, already here
  log.release(&merge, 0.0, 0.2);
  EXPECT_EQ(log.events, Events({"f1", "r50"}));  // 50 >= 1: the readings passed it
  merge.addFrame(2.0, 0.0, 2);
  EXPECT_FALSE(addMetres(&merge, 1.5, 1));  // older than 50: refused until restarted
  EXPECT_DOUBLE_EQ(merge.lastStamp(OdometryReading::kOdometer), 50.0);
  ASSERT_TRUE(addMetres(&merge, 60.0, 60));  // not handed on: dropped by the restart
  merge.restartReadings(OdometryReading::kOdometer);
  EXPECT_FALSE(merge.hasReadings());
  EXPECT_EQ(merge.waiting(), 1u);
  ASSERT_TRUE(addMetres(&merge, 1.5, 1));
  log.release(&merge, 0.0, 0.2);
  EXPECT_EQ(log.events, Events({"f1", "r50", "r1"}));  // 1.5 < 2: frame 2 waits
  ASSERT_TRUE(addMetres(&merge, 2.0, 2));
  log.release(&merge, 0.0, 0.2);
  EXPECT_EQ(log.events, Events({"f1", "r50", "r1", "r2", "f2"}));
}

TEST(OdometryMerge, AFrameWaitsForEverySourceThatSendsReadings) {
  OdometryMerge<int> merge;
  Log log;
  ASSERT_TRUE(addMetres(&merge, 1.0, 10));
  ASSERT_TRUE(addPosition(&merge, 0.9, 9));
  merge.addFrame(1.0, 100.0, 1);
  log.release(&merge, 100.01, 0.2);
  // The odometer reached 1.0, the positions only 0.9: the frame waits.
  EXPECT_EQ(log.events, Events({"p9", "r10"}));
  ASSERT_TRUE(addPosition(&merge, 1.1, 11));
  log.release(&merge, 100.02, 0.2);
  EXPECT_EQ(log.events, Events({"p9", "r10", "f1", "p11"}));
  EXPECT_TRUE(merge.hasReadings(OdometryReading::kPosition));
}

TEST(OdometryMerge, ReadingsOfTwoSourcesGoOnInStampOrder) {
  OdometryMerge<int> merge;
  Log log;
  merge.addFrame(1.7, 0.0, 1);
  // The odometer's 2.0 arrives before the position stamped 1.5.
  ASSERT_TRUE(addMetres(&merge, 2.0, 20));
  ASSERT_TRUE(addPosition(&merge, 1.5, 15));
  log.release(&merge, 0.0, 0.2);
  // Positions reached 1.5 < 1.7: the frame waits, the reading before it goes on.
  EXPECT_EQ(log.events, Events({"p15"}));
  ASSERT_TRUE(addPosition(&merge, 1.7, 17));
  log.release(&merge, 0.0, 0.2);
  EXPECT_EQ(log.events, Events({"p15", "p17", "f1", "r20"}));
}

TEST(OdometryMerge, RestartingOneSourceKeepsTheOthersReadings) {
  OdometryMerge<int> merge;
  Log log;
  merge.addFrame(1.0, 0.0, 1);
  ASSERT_TRUE(addMetres(&merge, 0.5, 5));
  ASSERT_TRUE(addPosition(&merge, 0.6, 6));
  ASSERT_TRUE(addMetres(&merge, 0.8, 8));
  merge.restartReadings(OdometryReading::kPosition);
  EXPECT_FALSE(merge.hasReadings(OdometryReading::kPosition));
  EXPECT_TRUE(merge.hasReadings());
  EXPECT_DOUBLE_EQ(merge.lastStamp(OdometryReading::kPosition), 0.0);
  EXPECT_DOUBLE_EQ(merge.lastStamp(OdometryReading::kOdometer), 0.8);
  ASSERT_TRUE(addMetres(&merge, 1.2, 12));
  log.release(&merge, 0.0, 0.2);
  // Only the odometer sends now: it reached the frame; the dropped position is gone.
  EXPECT_EQ(log.events, Events({"r5", "r8", "f1", "r12"}));
}

}  // namespace
}  // namespace bowg_ros
