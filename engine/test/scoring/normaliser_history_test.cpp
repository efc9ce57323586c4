// The normaliser history and floor (normaliser_history.h), with values worked
// out by hand.
#include "bowg/scoring/normaliser_history.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace bowg {
namespace {

TEST(NormaliserHistory, EmptyMedianIsZero) {
  const NormaliserHistory h;
  const Normalisers m = h.median();
  EXPECT_EQ(m.word, 0.0);
  EXPECT_EQ(m.group, 0.0);
  EXPECT_EQ(m.distribution, 0.0);
}

TEST(NormaliserHistory, OddCountTakesTheMiddleValuePerComponent) {
  NormaliserHistory h;
  // word 0.09, 0.02, 0.05 -> sorted 0.02 0.05 0.09: median 0.05.
  // group 0.010, 0.030, 0.020 -> 0.020. distribution 0.9, 0.8, 0.99 -> 0.9.
  h.push({0.09, 0.010, 0.9}, 10);
  h.push({0.02, 0.030, 0.8}, 10);
  h.push({0.05, 0.020, 0.99}, 10);
  const Normalisers m = h.median();
  EXPECT_DOUBLE_EQ(m.word, 0.05);
  EXPECT_DOUBLE_EQ(m.group, 0.020);
  EXPECT_DOUBLE_EQ(m.distribution, 0.9);
}

TEST(NormaliserHistory, EvenCountAveragesTheTwoMiddleValues) {
  NormaliserHistory h;
  // word 0.08, 0.02, 0.06, 0.04 -> sorted 0.02 0.04 0.06 0.08: (0.04+0.06)/2.
  h.push({0.08, 0, 0}, 10);
  h.push({0.02, 0, 0}, 10);
  h.push({0.06, 0, 0}, 10);
  h.push({0.04, 0, 0}, 10);
  EXPECT_DOUBLE_EQ(h.median().word, 0.05);
}

TEST(NormaliserHistory, KeepsOnlyTheLastWindowValues) {
  NormaliserHistory h;
  for (double w : {1.0, 2.0, 3.0, 4.0, 5.0}) h.push({w, 0, 0}, 3);
  ASSERT_EQ(h.size(), 3u);
  EXPECT_DOUBLE_EQ(h.values().front().word, 3.0);  // 1 and 2 fell out
  EXPECT_DOUBLE_EQ(h.median().word, 4.0);          // median of 3, 4, 5
  // A smaller window on the next push trims the older values.
  h.push({6.0, 0, 0}, 1);
  ASSERT_EQ(h.size(), 1u);
  EXPECT_DOUBLE_EQ(h.median().word, 6.0);
  EXPECT_THROW(h.push({1, 1, 1}, 0), std::invalid_argument);
}

TEST(NormaliserHistory, RestoreAndClear) {
  NormaliserHistory h;
  h.restore({{0.1, 0.2, 0.3}, {0.3, 0.4, 0.5}});
  EXPECT_EQ(h.size(), 2u);
  EXPECT_DOUBLE_EQ(h.median().group, 0.3);
  h.clear();
  EXPECT_EQ(h.size(), 0u);
}

TEST(NormaliserFloor, RaisesOnlyTheComponentsBelowTheFloor) {
  // floor 0.8 x expected (0.10, 0.020, 0.95) = (0.08, 0.016, 0.76).
  const Normalisers current{0.05, 0.030, 0.99};
  const Normalisers d = flooredNormalisers(current, {0.10, 0.020, 0.95}, 0.8);
  EXPECT_DOUBLE_EQ(d.word, 0.08);          // 0.05 < 0.08: raised
  EXPECT_DOUBLE_EQ(d.group, 0.030);        // 0.030 > 0.016: kept
  EXPECT_DOUBLE_EQ(d.distribution, 0.99);  // 0.99 > 0.76: kept
}

TEST(NormaliserFloor, ZeroFloorIsThePapersNormaliser) {
  const Normalisers current{0.01, 0.002, 0.5};
  const Normalisers d = flooredNormalisers(current, {0.1, 0.02, 0.99}, 0.0);
  EXPECT_EQ(d.word, 0.01);
  EXPECT_EQ(d.group, 0.002);
  EXPECT_EQ(d.distribution, 0.5);
  EXPECT_THROW(flooredNormalisers(current, current, -0.5), std::invalid_argument);
}

}  // namespace
}  // namespace bowg
