#include "bowg_pipe_sim/speed_profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bowg_pipe_sim/random.h"

namespace bowg {
namespace pipe_sim {
namespace {

// Stream id of the speed noise: 1-7 are roll, wobble, offset and exposure.
constexpr std::uint64_t kSpeedStream = 8;
constexpr int kSubSteps = 8;

}  // namespace

double speedAt(const SequenceOptions& o, double t) {
  const double v = o.speed_mps * (1 + o.speed_variation * smoothNoise(o.seed, kSpeedStream, t, o.speed_knot_s));
  return o.allow_reverse ? v : std::max(0.0, v);
}

std::vector<TravelSample> drive(double route_length, const SequenceOptions& o) {
  o.validate();
  const double step = o.speed_mps / o.frame_rate_hz;
  std::vector<TravelSample> samples;
  if (o.speed_variation == 0) {
    // i * step, not a running sum: a sum drifts in the last bits, and the
    // constant-speed sequence is the project's reference data.
    int frames = static_cast<int>(std::floor(route_length / step)) + 1;
    if (o.max_frames > 0) frames = std::min(frames, o.max_frames);
    samples.resize(frames);
    for (int i = 0; i < frames; ++i) samples[i].distance = samples[i].odometer = i * step;
    return samples;
  }
  const double nominal = std::floor(route_length / step) + 1;
  const double limit = 1000 * nominal;
  const double dt = 1 / (o.frame_rate_hz * kSubSteps);
  TravelSample s;
  samples.push_back(s);
  for (long i = 1; s.distance < route_length; ++i) {
    if (o.max_frames > 0 && static_cast<long>(samples.size()) >= o.max_frames) break;
    if (i > limit) {
      throw std::runtime_error("the speed profile (speed_variation " + std::to_string(o.speed_variation) +
                               ") does not reach the route's end within " +
                               std::to_string(static_cast<long>(limit)) + " frames");
    }
    double delta = 0;
    for (int k = 0; k < kSubSteps; ++k) delta += speedAt(o, ((i - 1) * kSubSteps + k + 0.5) * dt) * dt;
    const double next = std::max(0.0, std::min(route_length, s.distance + delta));
    s.odometer += std::abs(next - s.distance);
    s.distance = next;
    samples.push_back(s);
  }
  return samples;
}

}  // namespace pipe_sim
}  // namespace bowg
