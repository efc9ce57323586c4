#include "bowg_pipe_sim/odometry_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bowg {
namespace pipe_sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

using Matx66d = cv::Matx<double, 6, 6>;

void requireNonNegative(double value, const char* field) {
  // Infinity too: one infinite sigma turns every later pose into NaN.
  if (!(value >= 0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("OdometryNoise.") + field +
                                " must be a finite number >= 0");
  }
}

cv::Matx33d skew(const cv::Vec3d& v) {
  return cv::Matx33d(0, -v[2], v[1], v[2], 0, -v[0], -v[1], v[0], 0);
}

/// The rotation by |v| about v (Rodrigues); exactly the identity for v = 0,
/// so noise-free odometry is the truth to the last bit of dR.
cv::Matx33d rotationOf(const cv::Vec3d& v) {
  const double angle = cv::norm(v);
  if (angle == 0) return cv::Matx33d::eye();
  const cv::Matx33d k = skew(v * (1 / angle));
  return cv::Matx33d::eye() + k * std::sin(angle) + k * k * (1 - std::cos(angle));
}

void setBlock(Matx66d* m, int row, int col, const cv::Matx33d& block) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) (*m)(row + r, col + c) = block(r, c);
  }
}

}  // namespace

void OdometryNoise::validate() const {
  if (!(scale_bias >= -0.5 && scale_bias <= 0.5)) {
    throw std::invalid_argument("OdometryNoise.scale_bias must be in [-0.5, 0.5]");
  }
  requireNonNegative(scale_noise, "scale_noise");
  requireNonNegative(heading_drift_deg, "heading_drift_deg");
  requireNonNegative(roll_drift_deg, "roll_drift_deg");
}

OdometrySimulator::OdometrySimulator(const OdometryNoise& noise) : noise_(noise), rng_(noise.seed) {
  noise_.validate();
}

CameraPose OdometrySimulator::step(const CameraPose& truth) {
  if (!started_) {
    started_ = true;
    previous_truth_ = previous_odometry_ = truth;
    return truth;
  }
  const cv::Matx33d R_prev_t = previous_truth_.R_world_body.t();
  const cv::Matx33d dR = R_prev_t * truth.R_world_body;
  const cv::Vec3d dp = R_prev_t * (truth.position - previous_truth_.position);
  const double length = cv::norm(dp);

  // Always four draws per step, in this order, whatever the sigmas.
  const double n_scale = rng_.normal();
  const double n_roll = rng_.normal(), n_pitch = rng_.normal(), n_yaw = rng_.normal();

  // An odometer reports how far, not which way: a large negative draw stops
  // it rather than turning the step round.
  const double scale = std::max(0.0, 1 + noise_.scale_bias + noise_.scale_noise * n_scale);
  const cv::Vec3d dp_odometry = dp * scale;
  // A random walk in angle: the variance grows with the metres driven, so
  // the sigma of a step of length l is drift * sqrt(l) (frame rate and speed
  // do not change the drift per metre).
  const double root_length = std::sqrt(length);
  const double sigma_roll = noise_.roll_drift_deg * kDeg * root_length;
  const double sigma_heading = noise_.heading_drift_deg * kDeg * root_length;
  const cv::Vec3d angles(sigma_roll * n_roll, sigma_heading * n_pitch, sigma_heading * n_yaw);

  CameraPose odometry;
  odometry.leg = truth.leg;
  odometry.R_world_body = previous_odometry_.R_world_body * (dR * rotationOf(angles));
  const cv::Vec3d world_step = previous_odometry_.R_world_body * dp_odometry;
  odometry.position = previous_odometry_.position + world_step;

  // Covariance, errors e_p (position) and e_r (rotation about the fixed
  // axes, R' = exp(e_r) R'_mean): to first order the step adds
  // e_r x world_step to e_p, the distance noise along the step, and the
  // body-frame rotation noise turned into the odometry frame by R'_i.
  Matx66d F = Matx66d::eye();
  setBlock(&F, 0, 3, skew(world_step) * -1.0);
  const cv::Vec3d distance_sigma = previous_odometry_.R_world_body * dp * noise_.scale_noise;
  const cv::Matx33d body_rotation_variance(sigma_roll * sigma_roll, 0, 0,        //
                                           0, sigma_heading * sigma_heading, 0,  //
                                           0, 0, sigma_heading * sigma_heading);
  Matx66d Q = Matx66d::zeros();
  setBlock(&Q, 0, 0, distance_sigma * distance_sigma.t());
  setBlock(&Q, 3, 3, odometry.R_world_body * body_rotation_variance * odometry.R_world_body.t());
  covariance_ = F * covariance_ * F.t() + Q;

  true_distance_ += length;
  reported_distance_ += cv::norm(dp_odometry);
  previous_truth_ = truth;
  previous_odometry_ = odometry;
  return odometry;
}

std::vector<CameraPose> simulateOdometry(const std::vector<CameraPose>& truth,
                                         const OdometryNoise& noise) {
  OdometrySimulator simulator(noise);
  std::vector<CameraPose> odometry;
  odometry.reserve(truth.size());
  for (const CameraPose& pose : truth) odometry.push_back(simulator.step(pose));
  return odometry;
}

}  // namespace pipe_sim
}  // namespace bowg
