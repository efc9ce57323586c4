#include "bowg_pipe_sim/pipe_sequence.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

namespace bowg {
namespace pipe_sim {
namespace {

double wrap(double a) { return std::atan2(std::sin(a), std::cos(a)); }

TEST(PipeSequenceTest, FramesAreEvenlySpacedAndDeterministic) {
  const Route route(PipeNetwork::figureEight(), defaultRouteNodes(1), 0.12);
  SequenceOptions o;  // 0.2 m/s at 10 Hz: 0.02 m per frame
  const std::vector<FrameState> a = planSequence(route, o), b = planSequence(route, o);
  ASSERT_EQ(a.size(), static_cast<std::size_t>(std::floor(route.length() / 0.02)) + 1);
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_NEAR(a[i].distance, 0.02 * i, 1e-12);
    ASSERT_NEAR(a[i].stamp, o.start_stamp + 0.1 * i, 1e-6);
    ASSERT_EQ(a[i].roll_rad, b[i].roll_rad);
    ASSERT_EQ(a[i].exposure, b[i].exposure);
    // Roll within the amplitude; exposure within exp(+-(variation + step)).
    ASSERT_LE(std::abs(a[i].roll_rad), o.roll_amplitude_deg * M_PI / 180 + 1e-12);
    ASSERT_LE(std::abs(std::log(a[i].exposure)), o.exposure_variation + o.exposure_step + 1e-12);
    // The body x axis is the direction of travel up to the wobble.
    const cv::Vec3d x(a[i].pose.R_world_body(0, 0), a[i].pose.R_world_body(1, 0),
                      a[i].pose.R_world_body(2, 0));
    ASSERT_GT(x.dot(a[i].tangent), std::cos(2 * o.wobble_deg * M_PI / 180));
  }
  o.seed = 2;
  const std::vector<FrameState> c = planSequence(route, o);
  EXPECT_NE(c[100].roll_rad, a[100].roll_rad);
  o.max_frames = 10;
  EXPECT_EQ(planSequence(route, o).size(), 10u);
}

TEST(PipeSequenceTest, RollDiffersBetweenVisitsOfAPlace) {
  // The left circuit starts by driving 0 -> 1 again 14 m after the first
  // time: same place, another roll. Median over the whole first pipe.
  const Route route(PipeNetwork::figureEight(), defaultRouteNodes(1), 0.12);
  const std::vector<FrameState> f = planSequence(route, SequenceOptions());
  std::vector<double> diffs;
  // First visit: frames 15-85 (x = 0.3-1.7 m, 2 cm apart); second visit
  // 14 m later, frames 500-1000.
  for (int i = 15; i < 85; ++i) {
    int j = 500;
    for (int k = 500; k < 1000; ++k) {
      if (cv::norm(f[i].pose.position - f[k].pose.position) <
          cv::norm(f[i].pose.position - f[j].pose.position)) {
        j = k;
      }
    }
    ASSERT_LT(cv::norm(f[i].pose.position - f[j].pose.position), 0.02) << "frame " << j;
    diffs.push_back(std::abs(wrap(f[i].roll_rad - f[j].roll_rad)) * 180 / M_PI);
  }
  std::sort(diffs.begin(), diffs.end());
  EXPECT_GT(diffs[diffs.size() / 2], 10.0);
}

TEST(PipeSequenceTest, RejectsBadOptions) {
  SequenceOptions o;
  o.laps = 0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = SequenceOptions();
  o.frame_rate_hz = 0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = SequenceOptions();
  o.roll_amplitude_deg = 200;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  EXPECT_THROW(defaultRouteNodes(0), std::invalid_argument);
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
