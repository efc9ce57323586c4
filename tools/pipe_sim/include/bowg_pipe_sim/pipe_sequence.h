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
  /// Repetitions of the lap program (outer circuit, left circuit, right
  /// circuit, outer again: 48 m of pipe with the default network). >= 1.
  int laps = 1;
  /// Stop after this many frames (0 = drive the whole route).
  int max_frames = 0;
  double speed_mps = 0.2;       ///< along the centreline, > 0
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
  double network_width_m = 4.0;     ///< default network size (figure eight)
  double network_height_m = 3.0;
  double start_stamp = 1600000000.0;  ///< stamp of frame 0 (s since epoch)
  void validate() const;  ///< throws std::invalid_argument naming the field
};

/// The node sequence of `laps` laps of the default network.
std::vector<int> defaultRouteNodes(int laps);

struct FrameState {
  int index = 0;
  double stamp = 0;
  double distance = 0;  ///< driven along the route (m)
  CameraPose pose;
  cv::Vec3d tangent;    ///< direction of travel (for the ground truth)
  double roll_rad = 0;
  double exposure = 1;
};

/// One state per frame, frame i at distance i * speed / rate.
std::vector<FrameState> planSequence(const Route& route, const SequenceOptions& options);

}  // namespace pipe_sim
}  // namespace bowg
