#include "bowg_pipe_sim/pipe_sequence.h"

#include <cmath>
#include <stdexcept>

#include "bowg_pipe_sim/random.h"
#include "bowg_pipe_sim/speed_profile.h"

namespace bowg {
namespace pipe_sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

}  // namespace

void SequenceOptions::validate() const {
  if (laps < 1) throw std::invalid_argument("SequenceOptions.laps must be >= 1");
  if (max_frames < 0) throw std::invalid_argument("SequenceOptions.max_frames must be >= 0");
  if (!(speed_mps > 0)) throw std::invalid_argument("SequenceOptions.speed_mps must be > 0");
  if (!(frame_rate_hz > 0)) throw std::invalid_argument("SequenceOptions.frame_rate_hz must be > 0");
  if (!(roll_amplitude_deg >= 0) || roll_amplitude_deg > 180) {
    throw std::invalid_argument("SequenceOptions.roll_amplitude_deg must be in [0, 180]");
  }
  if (!(roll_knot_spacing_m > 0)) {
    throw std::invalid_argument("SequenceOptions.roll_knot_spacing_m must be > 0");
  }
  if (!(wobble_deg >= 0) || !(offset_m >= 0)) {
    throw std::invalid_argument("SequenceOptions.wobble_deg/offset_m must be >= 0");
  }
  if (!(exposure_variation >= 0) || !(exposure_step >= 0)) {
    throw std::invalid_argument("SequenceOptions.exposure_variation/exposure_step must be >= 0");
  }
  if (!(speed_variation >= 0) || !std::isfinite(speed_variation)) {
    throw std::invalid_argument("SequenceOptions.speed_variation must be >= 0");
  }
  if (!(speed_knot_s > 0) || !std::isfinite(speed_knot_s)) {
    throw std::invalid_argument("SequenceOptions.speed_knot_s must be > 0");
  }
  if (!(network_width_m > 0) || !(network_height_m > 0)) {
    throw std::invalid_argument("SequenceOptions.network_width_m/network_height_m must be > 0");
  }
}

std::vector<int> defaultRouteNodes(int laps) {
  if (laps < 1) throw std::invalid_argument("defaultRouteNodes: laps must be >= 1");
  // Outer circuit, left circuit (up the cross pipe), right circuit (down the
  // cross pipe), then the outer circuit's right and top sides back to 0: all
  // counter-clockwise, so the lap ends heading south into node 0 and the
  // next lap turns east without a U-turn.
  const int lap[] = {1, 2, 3, 4, 5, 0, 1, 4, 5, 0, 1, 2, 3, 4, 1, 2, 3, 4, 5, 0};
  std::vector<int> nodes{0};
  for (int l = 0; l < laps; ++l) nodes.insert(nodes.end(), std::begin(lap), std::end(lap));
  return nodes;
}

std::vector<FrameState> planSequence(const Route& route, const SequenceOptions& o) {
  o.validate();
  const std::vector<TravelSample> travel = drive(route.length(), o);
  const int frames = static_cast<int>(travel.size());
  std::vector<FrameState> states;
  states.reserve(frames);
  for (int i = 0; i < frames; ++i) {
    FrameState f;
    f.index = i;
    f.stamp = o.start_stamp + i / o.frame_rate_hz;
    f.distance = travel[i].distance;
    f.odometer = travel[i].odometer;
    const CentrelinePoint c = route.at(f.distance);
    f.tangent = c.tangent;
    // Body axes before roll: x along the pipe, y left, z up (horizontal
    // pipes; a vertical pipe takes world x as its reference).
    cv::Vec3d ref(0, 0, 1);
    if (std::abs(c.tangent.dot(ref)) > 0.9) ref = cv::Vec3d(1, 0, 0);
    const cv::Vec3d left = cv::normalize(ref.cross(c.tangent));
    const cv::Vec3d up = c.tangent.cross(left);
    f.roll_rad = o.roll_amplitude_deg * kDeg * smoothNoise(o.seed, 1, f.distance, o.roll_knot_spacing_m);
    const double yaw = o.wobble_deg * kDeg * smoothNoise(o.seed, 2, f.distance, 0.5);
    const double pitch = o.wobble_deg * kDeg * smoothNoise(o.seed, 3, f.distance, 0.5);
    // R = [t l u] * Rz(yaw) * Ry(pitch) * Rx(roll): roll about the pipe axis.
    const cv::Matx33d base(c.tangent[0], left[0], up[0], c.tangent[1], left[1], up[1],
                           c.tangent[2], left[2], up[2]);
    const double cr = std::cos(f.roll_rad), sr = std::sin(f.roll_rad);
    const double cp = std::cos(pitch), sp = std::sin(pitch);
    const double cy = std::cos(yaw), sy = std::sin(yaw);
    const cv::Matx33d Rx(1, 0, 0, 0, cr, -sr, 0, sr, cr);
    const cv::Matx33d Ry(cp, 0, sp, 0, 1, 0, -sp, 0, cp);
    const cv::Matx33d Rz(cy, -sy, 0, sy, cy, 0, 0, 0, 1);
    f.pose.R_world_body = base * Rz * Ry * Rx;
    f.pose.position = c.position + left * (o.offset_m * smoothNoise(o.seed, 4, f.distance, 1.0)) +
                      up * (o.offset_m * smoothNoise(o.seed, 5, f.distance, 1.0));
    f.pose.leg = c.leg;
    const double t = i / o.frame_rate_hz;
    const double smooth = o.exposure_variation * smoothNoise(o.seed, 6, t, 2.0);
    // Steps: piecewise constant over 8 s windows, 0.5 s transitions.
    const double window = std::floor(t / 8.0), within = t - 8.0 * window;
    const auto level = [&](double w) {
      return o.exposure_step * (2 * toUnit(hashCombine(o.seed, 7, static_cast<std::uint64_t>(static_cast<long long>(w)))) - 1);
    };
    const double blend = std::min(1.0, within / 0.5);
    const double stepped = level(window - 1) * (1 - blend) + level(window) * blend;
    f.exposure = std::exp(smooth + stepped);
    states.push_back(f);
  }
  return states;
}

}  // namespace pipe_sim
}  // namespace bowg
