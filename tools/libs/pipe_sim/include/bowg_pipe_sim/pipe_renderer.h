// Renders what a forward-looking robot camera with a ring light sees inside
// the pipe network, by ray casting: every pixel's ray is followed through the
// mitred pipe regions of the route (current pipe, elbows to the next and
// previous pipes) and into side branches at T-junctions, until it meets the
// wall; the wall's albedo comes from WallTexture. Bends are mitred elbows
// (two straight cylinders cut by the bisector plane), not tori.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/wall_texture.h"

namespace bowg {
namespace pipe_sim {

/// Pinhole camera without distortion; pixel centres at integer coordinates.
struct CameraModel {
  int width = 640, height = 480;
  double fx = 320, fy = 320;  ///< px (320 at 640 px: 90 deg horizontal field of view)
  double cx = 319.5, cy = 239.5;
  void validate() const;  ///< throws std::invalid_argument naming the field
};

/// The ring light around the lens: irradiance power * cos(incidence) /
/// (d^2 + core^2) * exp(-d / falloff) * cos(off-axis angle)^beam_exponent.
struct LightModel {
  double power = 0.03;       ///< chosen so the near wall is just below saturation
  double core_m = 0.05;      ///< the ring's size: no singularity at d -> 0
  double falloff_m = 3.0;    ///< extra attenuation (scattering, dirt on the lens)
  double beam_exponent = 2;  ///< LED beam pattern and lens vignetting together
  void validate() const;
};

/// Sensor: linear signal -> shot noise -> gamma -> read noise -> 8 bit.
struct SensorModel {
  double shot_noise = 0.0005;   ///< photon noise: variance per unit of linear signal (1 = white)
  double read_noise = 2.0;      ///< std dev of the additive noise after the response curve (DN)
  double gamma = 1 / 2.6;       ///< output = 255 * linear^gamma (a log-like camera response)
  double blur_sigma_px = 0.6;   ///< optics blur, applied before the noise
  double max_distance_m = 4.0;  ///< rays travelling farther return black
  void validate() const;
};

/// Camera body pose: R_world_body columns are the body's x (forward, along
/// the optical axis), y (left) and z (up) axes in the world (REP-103 body
/// convention); the optical frame is z forward, x right, y down.
struct CameraPose {
  cv::Vec3d position;
  cv::Matx33d R_world_body = cv::Matx33d::eye();
  int leg = 0;  ///< route leg whose render region holds the camera
};

class PipeRenderer {
 public:
  /// Keeps references to the network, route and texture: they must outlive
  /// the renderer.
  PipeRenderer(const PipeNetwork& network, const Route& route, const WallTexture& texture,
               const CameraModel& camera, const LightModel& light, const SensorModel& sensor);

  /// An 8-bit grey image. `exposure` scales the linear signal (1 = nominal);
  /// `noise_seed` selects the noise pattern (same seed, same image).
  cv::Mat render(const CameraPose& pose, double exposure, std::uint64_t noise_seed) const;

  /// The noise-free linear irradiance image (CV_32F, albedo x light), for
  /// tests: a wall point's value does not depend on the noise.
  cv::Mat renderLinear(const CameraPose& pose) const;

  const CameraModel& camera() const { return camera_; }

 private:
  struct Region;
  class RayCaster;  // renderLinear's per-frame state and per-pixel steps (pipe_ray_caster.cpp)
  void buildRegions(int leg, std::vector<Region>& regions, int& current) const;

  const PipeNetwork& network_;
  const Route& route_;
  const WallTexture& texture_;
  CameraModel camera_;
  LightModel light_;
  SensorModel sensor_;
  std::vector<cv::Vec3f> rays_optical_;  // unit ray per pixel, row-major
  std::vector<float> beam_;              // cos(off-axis)^beam_exponent per pixel
  std::vector<float> noise_table_;       // standard normal samples
  static constexpr int kResponseSize = 4096;
  std::vector<float> response_;  // 8-bit output over sqrt(linear)
  std::vector<std::vector<int>> node_edges_;
};

/// Row-major 3x3 rotation -> unit quaternion (x, y, z, w), w >= 0.
cv::Vec4d rotationToQuaternion(const cv::Matx33d& R);

}  // namespace pipe_sim
}  // namespace bowg
