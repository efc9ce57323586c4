// Odometry that drifts as a crawler's wheel or tether odometer does in a
// pipe: the true motion between consecutive frames, measured in the previous
// body frame, with its length over-reported by a slip factor and per-step
// noise, and its rotation perturbed by a random walk whose variance grows with
// the metres driven; the perturbed steps are chained, so the errors
// accumulate as they do on a robot. For the pose-graph examples, which need
// odometry whose drift loop closures can correct. See docs/pipe_sequence.md
// ("Odometry") for the model in words.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/random.h"

namespace bowg {
namespace pipe_sim {

struct OdometryNoise {
  /// Fraction of the distance over-reported (slip of a wheel, stretch of a
  /// tether; negative: under-reported), in [-0.5, 0.5].
  double scale_bias = 0.03;
  /// Per-step relative sigma of the distance, >= 0.
  double scale_noise = 0.02;
  /// Random walk of yaw and pitch (about body z and y): sigma in deg per
  /// sqrt(metre driven), >= 0.
  double heading_drift_deg = 1.0;
  /// Random walk of roll (about body x, forward): deg per sqrt(metre), >= 0.
  double roll_drift_deg = 1.0;
  std::uint64_t seed = 1;
  void validate() const;  ///< throws std::invalid_argument naming the field
};

/// The odometry frame by frame, for sequences too long to hold twice: feed
/// the true poses in frame order.
///
/// Per step, with dR = R_{i-1}^T R_i and dp = R_{i-1}^T (p_i - p_{i-1}) the
/// true motion in the previous body frame (REP-103: x forward, y left, z up):
///   dp' = dp * max(0, 1 + scale_bias + scale_noise * n0)
///   dR' = dR * exp([roll_drift * n1, heading_drift * n2, heading_drift * n3]
///                  * sqrt(|dp|))
///   R'_i = R'_{i-1} dR',  p'_i = p'_{i-1} + R'_{i-1} dp'
/// n0..n3 standard normals from Random(seed), four per step whatever the
/// sigmas (so switching one noise off leaves the others' draws unchanged).
/// The scale multiplies the whole step vector, so a robot backing up (dp
/// along -x) over-reports the way back as it does the way forward.
class OdometrySimulator {
 public:
  /// Throws std::invalid_argument (OdometryNoise::validate) for bad noise.
  explicit OdometrySimulator(const OdometryNoise& noise);

  /// The odometry pose of the next frame, whose true pose is `truth`; the
  /// first call returns `truth` itself (the odometry frame starts at the
  /// true pose). `leg` is copied from `truth`: it is the renderer's
  /// bookkeeping, not something odometry measures.
  CameraPose step(const CameraPose& truth);

  /// First-order covariance of the latest pose's random error: rows and
  /// columns x, y, z (m) and rotation about the fixed x, y, z axes of the
  /// odometry frame (rad), the order and convention of ROS's
  /// PoseWithCovariance. It propagates scale_noise and the rotation random
  /// walks along the odometry's own trajectory; scale_bias is a systematic
  /// error and not in it. Zero before the second step.
  const cv::Matx<double, 6, 6>& covariance() const { return covariance_; }

  /// Metres of true motion (sum of |dp|) and of reported motion (sum of
  /// |dp'|) so far.
  double trueDistance() const { return true_distance_; }
  double reportedDistance() const { return reported_distance_; }

 private:
  OdometryNoise noise_;
  Random rng_;
  bool started_ = false;
  CameraPose previous_truth_, previous_odometry_;
  cv::Matx<double, 6, 6> covariance_ = cv::Matx<double, 6, 6>::zeros();
  double true_distance_ = 0, reported_distance_ = 0;
};

/// OdometrySimulator over a whole trajectory: output[i] is the odometry pose
/// of truth[i], output[0] == truth[0]. Deterministic for noise.seed on every
/// platform (Random, not std::normal_distribution).
std::vector<CameraPose> simulateOdometry(const std::vector<CameraPose>& truth,
                                         const OdometryNoise& noise);

}  // namespace pipe_sim
}  // namespace bowg
