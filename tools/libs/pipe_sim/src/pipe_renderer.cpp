#include "bowg_pipe_sim/pipe_renderer.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "bowg_pipe_sim/random.h"

namespace bowg {
namespace pipe_sim {

void CameraModel::validate() const {
  if (width < 16 || height < 16)
    throw std::invalid_argument("CameraModel: width/height must be >= 16");
  if (!(fx > 0) || !(fy > 0)) throw std::invalid_argument("CameraModel: fx/fy must be > 0");
}
void LightModel::validate() const {
  if (!(power > 0)) throw std::invalid_argument("LightModel.power must be > 0");
  if (!(core_m >= 0)) throw std::invalid_argument("LightModel.core_m must be >= 0");
  if (!(falloff_m > 0)) throw std::invalid_argument("LightModel.falloff_m must be > 0");
  if (!(beam_exponent >= 0)) throw std::invalid_argument("LightModel.beam_exponent must be >= 0");
}
void SensorModel::validate() const {
  if (!(read_noise >= 0) || !(shot_noise >= 0)) {
    throw std::invalid_argument("SensorModel: read_noise/shot_noise must be >= 0");
  }
  if (!(gamma > 0)) throw std::invalid_argument("SensorModel.gamma must be > 0");
  if (!(blur_sigma_px >= 0)) throw std::invalid_argument("SensorModel.blur_sigma_px must be >= 0");
  if (!(max_distance_m > 0)) throw std::invalid_argument("SensorModel.max_distance_m must be > 0");
}

PipeRenderer::PipeRenderer(const PipeNetwork& network, const Route& route,
                           const WallTexture& texture, const CameraModel& camera,
                           const LightModel& light, const SensorModel& sensor)
    : network_(network),
      route_(route),
      texture_(texture),
      camera_(camera),
      light_(light),
      sensor_(sensor) {
  camera_.validate();
  light_.validate();
  sensor_.validate();
  rays_optical_.resize(static_cast<std::size_t>(camera_.width) * camera_.height);
  for (int v = 0; v < camera_.height; ++v) {
    for (int u = 0; u < camera_.width; ++u) {
      rays_optical_[static_cast<std::size_t>(v) * camera_.width + u] =
          cv::normalize(cv::Vec3f(static_cast<float>((u - camera_.cx) / camera_.fx),
                                  static_cast<float>((v - camera_.cy) / camera_.fy), 1.f));
    }
  }
  beam_.resize(rays_optical_.size());
  for (std::size_t i = 0; i < rays_optical_.size(); ++i) {
    beam_[i] = static_cast<float>(std::pow(rays_optical_[i][2], light_.beam_exponent));
  }
  // Sensor response as a table over sqrt(linear): fine steps in the darks,
  // where the gamma curve is steep.
  response_.resize(kResponseSize);
  for (int i = 0; i < kResponseSize; ++i) {
    const double root = static_cast<double>(i) / (kResponseSize - 1);
    response_[i] = static_cast<float>(255.0 * std::pow(root * root, sensor_.gamma) + 0.5);
  }
  Random rng(0x6e6f697365ULL);  // fixed: the table is part of the renderer
  noise_table_.resize(1 << 20);
  for (float& n : noise_table_) n = static_cast<float>(rng.normal());
  node_edges_.resize(network_.nodes.size());
  for (std::size_t e = 0; e < network_.edges.size(); ++e) {
    node_edges_[network_.edges[e].from].push_back(static_cast<int>(e));
    node_edges_[network_.edges[e].to].push_back(static_cast<int>(e));
  }
}

// renderLinear, the ray casting, is in pipe_ray_caster.cpp.
cv::Mat PipeRenderer::render(const CameraPose& pose, double exposure,
                             std::uint64_t noise_seed) const {
  cv::Mat linear = renderLinear(pose);
  if (sensor_.blur_sigma_px > 0) {
    cv::GaussianBlur(linear, linear, cv::Size(0, 0), sensor_.blur_sigma_px);
  }
  const std::size_t mask = noise_table_.size() - 1;
  std::size_t k = splitMix64(noise_seed) & mask;
  const std::size_t stride = (splitMix64(noise_seed + 1) & 0xffff) * 2 + 1;  // odd: full cycle
  const float read = static_cast<float>(sensor_.read_noise);
  const float shot = static_cast<float>(sensor_.shot_noise);
  const std::size_t second = noise_table_.size() / 2;  // an unrelated second sample
  const float gain = static_cast<float>(exposure);
  cv::Mat image(linear.size(), CV_8U);
  for (int v = 0; v < linear.rows; ++v) {
    const float* in = linear.ptr<float>(v);
    uchar* px = image.ptr<uchar>(v);
    for (int u = 0; u < linear.cols; ++u) {
      const float s = gain * in[u];
      // Photon noise before the response curve, read-out noise after it (it
      // is what stays visible in the dark centre of the pipe).
      const float noisy = s + std::sqrt(shot * s) * noise_table_[k];
      const float root = noisy > 0 ? std::sqrt(std::min(noisy, 1.f)) : 0.f;
      const float dn = response_[static_cast<int>(root * (kResponseSize - 1))] +
                       read * noise_table_[(k + second) & mask];
      k = (k + stride) & mask;
      px[u] = static_cast<uchar>(std::max(0.f, std::min(255.f, dn)));
    }
  }
  return image;
}

cv::Vec4d rotationToQuaternion(const cv::Matx33d& R) {
  // Shepperd's method: pick the largest of w, x, y, z for stability.
  const double tr = R(0, 0) + R(1, 1) + R(2, 2);
  double x, y, z, w;
  if (tr > 0) {
    const double s = std::sqrt(tr + 1.0) * 2;
    w = 0.25 * s;
    x = (R(2, 1) - R(1, 2)) / s;
    y = (R(0, 2) - R(2, 0)) / s;
    z = (R(1, 0) - R(0, 1)) / s;
  } else if (R(0, 0) > R(1, 1) && R(0, 0) > R(2, 2)) {
    const double s = std::sqrt(1.0 + R(0, 0) - R(1, 1) - R(2, 2)) * 2;
    w = (R(2, 1) - R(1, 2)) / s;
    x = 0.25 * s;
    y = (R(0, 1) + R(1, 0)) / s;
    z = (R(0, 2) + R(2, 0)) / s;
  } else if (R(1, 1) > R(2, 2)) {
    const double s = std::sqrt(1.0 + R(1, 1) - R(0, 0) - R(2, 2)) * 2;
    w = (R(0, 2) - R(2, 0)) / s;
    x = (R(0, 1) + R(1, 0)) / s;
    y = 0.25 * s;
    z = (R(1, 2) + R(2, 1)) / s;
  } else {
    const double s = std::sqrt(1.0 + R(2, 2) - R(0, 0) - R(1, 1)) * 2;
    w = (R(1, 0) - R(0, 1)) / s;
    x = (R(0, 2) + R(2, 0)) / s;
    y = (R(1, 2) + R(2, 1)) / s;
    z = 0.25 * s;
  }
  cv::Vec4d q(x, y, z, w);
  q /= cv::norm(q);
  if (q[3] < 0) q = -q;
  return q;
}

}  // namespace pipe_sim
}  // namespace bowg
