// The in-pipe sequence: the route driven through the default network, the
// camera's pose per frame (centreline + roll that differs between visits +
// small pitch/yaw jitter), and the exposure per frame. Everything is a pure
// function of SequenceOptions (deterministic for a seed). See
// docs/pipe_sequence.md for the definitions and the defaults.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/pipe_renderer.h"

namespace bowg {
namespace pipe_sim {

struct SequenceOptions {
  std::uint64_t seed = 1;
  /// Repetitions of the lap program (defaultRouteNodes: outer circuit, left
  /// circuit, right circuit, outer again: 48 m of pipe with the default
  /// network; or the route program's, route_programs.h). >= 1.
  int laps = 1;
  /// Stop after this many frames (0 = drive the whole route).
  int max_frames = 0;
  double speed_mps = 0.2;       ///< mean speed along the centreline, > 0
  /// Speed profile, >= 0: speed(t) = speed_mps * (1 + speed_variation * n(t)),
  /// n a smooth noise in [-1, 1] with knots every speed_knot_s seconds. Real
  /// crawlers slow down, stop and surge (tether drag, debris, the operator);
  /// 0 = constant speed (frames exactly speed / rate apart).
  double speed_variation = 0.0;
  double speed_knot_s = 4.0;  ///< > 0
  /// Where speed(t) < 0: true = the robot backs up (the camera still faces
  /// the route's forward direction), false = it stands still.
  bool allow_reverse = false;
  /// Camera rate, > 0: 0.02 m between frames. In a 6-inch pipe the near wall
  /// is 0.1 m away: at 0.05 m spacing consecutive frames (and a revisit's
  /// nearest frame) share hardly any verifiable feature.
  double frame_rate_hz = 10.0;
  /// Roll about the pipe axis: a smooth random function of the distance
  /// driven, uniform in [-amplitude, amplitude] at knots every
  /// roll_knot_spacing_m, so two visits of a place see different rolls.
  double roll_amplitude_deg = 60.0;
  double roll_knot_spacing_m = 3.0;
  /// Pitch/yaw wobble of the crawler (deg) and centreline offset (m).
  double wobble_deg = 1.5;
  double offset_m = 0.004;
  /// Auto-exposure: log-gain varies smoothly by +-exposure_variation, plus
  /// steps of up to +-exposure_step every ~8 s.
  double exposure_variation = 0.2;
  double exposure_step = 0.15;
  double bend_radius_m = 0.12;      ///< centreline fillet radius at bends
  double network_width_m = 4.0;     ///< default network size (figure eight), > 0
  double network_height_m = 3.0;    ///< > 0
  double start_stamp = 1600000000.0;  ///< stamp of frame 0 (s since epoch)
  void validate() const;  ///< throws std::invalid_argument naming the field
};

/// The node sequence of `laps` laps of the default network.
std::vector<int> defaultRouteNodes(int laps);

struct FrameState {
  int index = 0;
  double stamp = 0;
  /// Position along the route (m): what the place, roll and wobble are
  /// functions of; decreases while the robot backs up.
  double distance = 0;
  /// Metres driven since frame 0, forward and backward alike (never
  /// decreases): what "the immediate past" of the ground truth is measured in.
  double odometer = 0;
  CameraPose pose;
  /// The route's forward direction at `distance`: the way the camera looks
  /// (also while backing up), which decides what it sees (ground truth).
  cv::Vec3d tangent;
  double roll_rad = 0;
  double exposure = 1;
};

/// One state per frame, frame i at stamp start_stamp + i / rate, its
/// distance from the speed profile (drive(), speed_profile.h): i * speed /
/// rate at constant speed. Ends at the route's end or after max_frames.
std::vector<FrameState> planSequence(const Route& route, const SequenceOptions& options);

}  // namespace pipe_sim
}  // namespace bowg
