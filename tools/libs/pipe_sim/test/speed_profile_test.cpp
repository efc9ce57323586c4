#include "bowg_pipe_sim/speed_profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/random.h"

namespace bowg {
namespace pipe_sim {
namespace {

std::vector<double> spacings(const std::vector<TravelSample>& s) {
  std::vector<double> d;
  for (std::size_t i = 1; i < s.size(); ++i) d.push_back(s[i].distance - s[i - 1].distance);
  return d;
}

TEST(SpeedProfileTest, ConstantSpeedIsExactlyEvenlySpaced) {
  // The reference sequence: frame i at exactly i * step, reverse or not.
  SequenceOptions o;
  o.frame_rate_hz = 5;
  for (bool reverse : {false, true}) {
    o.allow_reverse = reverse;
    const std::vector<TravelSample> s = drive(10.0, o);
    ASSERT_EQ(s.size(), 251u);  // floor(10 / 0.04) + 1
    for (std::size_t i = 0; i < s.size(); ++i) {
      ASSERT_EQ(s[i].distance, i * (0.2 / 5));
      ASSERT_EQ(s[i].odometer, s[i].distance);
    }
  }
}

TEST(SpeedProfileTest, VaryingSpeedVariesTheSpacingButNeverGoesBack) {
  SequenceOptions o;
  o.speed_variation = 0.8;
  const double step = o.speed_mps / o.frame_rate_hz, length = 47.0;
  const std::vector<TravelSample> s = drive(length, o);
  const std::vector<double> d = spacings(s);
  const auto range = std::minmax_element(d.begin(), d.end());
  EXPECT_GE(*range.first, 0.0);
  EXPECT_LT(*range.first, 0.5 * step);  // slow: dense frames
  EXPECT_GT(*range.second, 1.5 * step);  // fast: sparse frames
  EXPECT_LE(*range.second, (1 + o.speed_variation) * step + 1e-12);
  for (const TravelSample& t : s) ASSERT_EQ(t.odometer, t.distance);
  // The mean speed stays about speed_mps: as many frames as at constant
  // speed within 25 %.
  EXPECT_NEAR(static_cast<double>(s.size()), length / step, 0.25 * length / step);
  // Deterministic, and another seed drives differently.
  const std::vector<TravelSample> again = drive(length, o);
  ASSERT_EQ(again.size(), s.size());
  for (std::size_t i = 0; i < s.size(); ++i) ASSERT_EQ(again[i].distance, s[i].distance);
  o.seed = 2;
  EXPECT_NE(drive(length, o)[100].distance, s[100].distance);
}

TEST(SpeedProfileTest, WithoutReverseANegativeSpeedIsAStop) {
  SequenceOptions o;
  o.speed_variation = 2.0;  // speed(t) < 0 wherever n(t) < -0.5
  const std::vector<double> d = spacings(drive(30.0, o));
  const long stops = std::count(d.begin(), d.end(), 0.0);
  EXPECT_GT(stops, 10);
  EXPECT_GE(*std::min_element(d.begin(), d.end()), 0.0);
  EXPECT_EQ(speedAt(o, 0.0) >= 0, true);
  for (double t = 0; t < 60; t += 0.37) ASSERT_GE(speedAt(o, t), 0.0);
}

TEST(SpeedProfileTest, ReverseBacksUpAndTheOdometerKeepsCounting) {
  SequenceOptions o;
  o.speed_variation = 2.0;
  o.allow_reverse = true;
  const double length = 30.0;
  const std::vector<TravelSample> s = drive(length, o);
  const std::vector<double> d = spacings(s);
  EXPECT_LT(*std::min_element(d.begin(), d.end()), 0.0);
  for (std::size_t i = 1; i < s.size(); ++i) {
    ASSERT_GE(s[i].odometer, s[i - 1].odometer);
    ASSERT_NEAR(s[i].odometer - s[i - 1].odometer, std::abs(d[i - 1]), 1e-9);
    ASSERT_GE(s[i].distance, 0.0);
  }
  // Backing up is driving too: the odometer ends beyond the route length.
  EXPECT_GT(s.back().odometer, length + 0.5);
}

TEST(SpeedProfileTest, TheRouteEndEndsTheSequence) {
  SequenceOptions o;
  o.speed_variation = 0.8;
  const double length = 3.0;
  const std::vector<TravelSample> s = drive(length, o);
  EXPECT_EQ(s.back().distance, length);
  for (std::size_t i = 0; i + 1 < s.size(); ++i) ASSERT_LT(s[i].distance, length);
  o.max_frames = 7;
  EXPECT_EQ(drive(length, o).size(), 7u);
}

TEST(SpeedProfileTest, PlaceDependsOnDistanceExposureOnTime) {
  // A place looks the same however fast the robot passes it (roll is a
  // function of the position along the route), the auto exposure keeps its
  // own clock (frame i has the exposure of frame i at constant speed).
  const Route route(PipeNetwork::figureEight(), defaultRouteNodes(1), 0.12);
  SequenceOptions o;
  o.max_frames = 600;
  const std::vector<FrameState> constant = planSequence(route, o);
  o.speed_variation = 1.5;
  o.allow_reverse = true;
  const std::vector<FrameState> varying = planSequence(route, o);
  ASSERT_EQ(varying.size(), 600u);
  bool moved_differently = false;
  for (std::size_t i = 0; i < varying.size(); ++i) {
    const FrameState& f = varying[i];
    ASSERT_EQ(f.exposure, constant[i].exposure);
    ASSERT_DOUBLE_EQ(f.stamp, constant[i].stamp);
    ASSERT_DOUBLE_EQ(f.roll_rad, o.roll_amplitude_deg * M_PI / 180 *
                                     smoothNoise(o.seed, 1, f.distance, o.roll_knot_spacing_m));
    moved_differently = moved_differently || std::abs(f.distance - constant[i].distance) > 0.1;
    // The camera faces the route's forward direction, also while backing up.
    const cv::Vec3d x(f.pose.R_world_body(0, 0), f.pose.R_world_body(1, 0), f.pose.R_world_body(2, 0));
    ASSERT_GT(x.dot(route.at(f.distance).tangent), 0.99);
  }
  EXPECT_TRUE(moved_differently);
}

TEST(SpeedProfileTest, RejectsBadOptions) {
  SequenceOptions o;
  o.speed_variation = -0.1;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = SequenceOptions();
  o.speed_knot_s = 0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = SequenceOptions();
  o.network_width_m = 0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
