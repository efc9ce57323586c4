// The steps of a loop's metric translation (metric_translation.h), in the
// order estimateMetricTranslation runs them: which neighbours can help, each
// neighbour's pose in metres, the loop inliers triangulated, the loop's pose
// by PnP refined with the depths, and the covariance by bootstrap. Private to
// the engine; separate so that each step can be tested alone.
#pragma once

#include <array>
#include <cstddef>
#include <opencv2/core.hpp>
#include <random>
#include <utility>
#include <vector>

#include "bowg/detection/metric_translation.h"
#include "detection/metric_geometry.h"

namespace bowg {
namespace metric_steps {

/// The neighbours' candidate correspondences with the match M (as the
/// loop's verification finds them) and how many loop inliers they could
/// give a depth: RANSAC is the cost, so the count decides first whether
/// min_points is reachable at all.
struct NeighbourCandidates {
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> pairs;  ///< per neighbour
  std::vector<int> covering;  ///< per neighbour: loop inliers among its pairs
  int coverable = 0;          ///< loop inliers seen by at least one neighbour
};
NeighbourCandidates findNeighbourCandidates(const std::vector<Correspondence>& loop_inliers,
                                            const VerificationView& match,
                                            const std::vector<ScaleNeighbour>& neighbours,
                                            const GeometricVerificationOptions& geometric);

/// One neighbour N of the match M: their inlier correspondences (M feature
/// as "query", N feature as "match"), N's pose in M scaled by the odometer,
/// and which pair sees each M feature.
struct NeighbourTrack {
  const ScaleNeighbour* input = nullptr;
  std::vector<Correspondence> pairs;
  double r[9], u[3];
  metric_geometry::NeighbourPose pose;
  std::vector<int> pair_of_feature;  ///< M feature -> index into pairs, -1
};

/// Step 1: the pose of each useful neighbour in M, up to scale by the
/// fundamental and essential matrices, refitted on every pair it agrees
/// with, then in metres by the neighbour's baseline. Neighbours without a
/// pose are left out.
std::vector<NeighbourTrack> poseNeighbours(const NeighbourCandidates& candidates,
                                           const VerificationView& match,
                                           const std::vector<ScaleNeighbour>& neighbours,
                                           const CameraIntrinsics& match_intrinsics,
                                           const GeometricVerificationOptions& geometric);

/// A triangulated loop inlier: its neighbour, its pair there, the query pixel.
struct PointSource {
  std::size_t neighbour;
  std::size_t pair;
  cv::Point2d pixel;
};
struct TriangulatedLoop {
  std::vector<cv::Point3d> points;  ///< in M's frame, metres
  std::vector<PointSource> sources;
};

/// Step 2: the loop inliers a neighbour sees, triangulated in M's frame
/// (by the first neighbour that triangulates each).
TriangulatedLoop triangulateLoopInliers(const std::vector<Correspondence>& loop_inliers,
                                        const std::vector<NeighbourTrack>& tracks,
                                        const cv::Matx33d& K, double threshold_px);

/// The loop's pose T_Q_M fitted to the triangulated points, and what the
/// covariance needs from the fit.
struct LoopPoseFit {
  cv::Vec3d rvec, tvec;              ///< T_Q_M: Rodrigues vector and metres
  std::vector<PointSource> inliers;  ///< the PnP inliers' sources
  int inlier_count = 0;
  double rms_px = 0;            ///< the inliers' RMS reprojection error
  double fit_sigma_px = 0;      ///< the residual sigma (6 dof removed)
  cv::Matx66d pose_covariance;  ///< (J^T J)^-1 of the pose's 6 parameters
};

/// Step 3: PnP by RANSAC (twice the verification's threshold: the points
/// carry their triangulation error into the query), least squares on its
/// inliers, then pose and depths refined together (refineJointly). Returns
/// kEstimated or why it failed (kPerspectiveFailed); `fit->inlier_count` is
/// set either way.
MetricTranslationStatus fitLoopPose(const TriangulatedLoop& loop,
                                    const std::vector<NeighbourTrack>& tracks,
                                    const CameraIntrinsics& query_intrinsics, const cv::Matx33d& K,
                                    const GeometricVerificationOptions& geometric,
                                    const MetricTranslationOptions& options, LoopPoseFit* fit);

/// Step 4a: the bootstrap. Each sample resamples with replacement every
/// neighbour's pairs (refitting its pose) and the loop's points, and refines
/// the pose again from the estimate; the translations of the samples that
/// hold up. Deterministic for a given `rng` state.
std::vector<cv::Vec3d> bootstrapTranslations(const std::vector<NeighbourTrack>& tracks,
                                             const LoopPoseFit& fit,
                                             const CameraIntrinsics& query_intrinsics,
                                             const cv::Matx33d& K, int samples, std::mt19937* rng);

/// Step 4b: the covariance of t (row-major 3x3, m^2):
///   covariance_scale * (S + sigma^2 C_t + f^2 t t^T)
/// with S the bootstrap samples' spread (unbiased), sigma the fit's residual
/// sigma (at least kPixelNoiseFloor px) through C_t, the translation block
/// of (J^T J)^-1 (symmetrised), and f the odometer's relative error.
std::array<double, 9> translationCovariance(const std::vector<cv::Vec3d>& samples,
                                            const LoopPoseFit& fit,
                                            const MetricTranslationOptions& options);

/// Corner positions are good to a fraction of a pixel, not better: the
/// covariance's noise never drops below this even when the fit is exact.
constexpr double kPixelNoiseFloor = 0.3;

}  // namespace metric_steps
}  // namespace bowg
