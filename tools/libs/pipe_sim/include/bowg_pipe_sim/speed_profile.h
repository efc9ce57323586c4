// Where the robot is at every frame: the camera runs at a fixed rate while
// the crawler's speed varies (SequenceOptions::speed_variation), so frames
// are dense where it is slow or stopped and sparse where it surges; with
// allow_reverse it also backs up. Separate from the pose so that the
// spacing can be tested on its own.
#pragma once

#include <vector>

#include "bowg_pipe_sim/pipe_sequence.h"

namespace bowg {
namespace pipe_sim {

struct TravelSample {
  double distance = 0;  ///< position along the route (m), in [0, route length]
  double odometer = 0;  ///< |metres| driven since frame 0, non-decreasing
};

/// Speed (m/s) at time t (s since frame 0): speed_mps * (1 + speed_variation
/// * n(t)), clamped at 0 unless allow_reverse.
double speedAt(const SequenceOptions& options, double t);

/// One sample per frame from distance 0. At constant speed frame i is at
/// exactly i * speed / rate (floor(length / step) + 1 frames, as always);
/// otherwise the speed is integrated between frames (midpoint rule, 8
/// sub-steps), the position clamped to [0, route_length], and the sequence
/// ends with the first frame at the route's end. Both stop after max_frames
/// (> 0). Throws std::runtime_error when the profile does not reach the end
/// within 1000 times the frames of constant speed (a robot that never
/// arrives is an option mistake, not a sequence).
std::vector<TravelSample> drive(double route_length, const SequenceOptions& options);

}  // namespace pipe_sim
}  // namespace bowg
