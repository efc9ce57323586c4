#include "bowg/detection/metric_translation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <random>

#include "detection/metric_translation_steps.h"

namespace bowg {

const char* toString(MetricTranslationStatus s) {
  switch (s) {
    case MetricTranslationStatus::kEstimated:
      return "estimated";
    case MetricTranslationStatus::kDisabled:
      return "disabled";
    case MetricTranslationStatus::kNoOdometry:
      return "no_odometry";
    case MetricTranslationStatus::kNoNeighbour:
      return "no_neighbour";
    case MetricTranslationStatus::kNoNeighbourPose:
      return "no_neighbour_pose";
    case MetricTranslationStatus::kTooFewPoints:
      return "too_few_points";
    case MetricTranslationStatus::kPerspectiveFailed:
      return "perspective_failed";
    case MetricTranslationStatus::kOutsideOdometry:
      return "outside_odometry";
  }
  return "unknown";
}

std::vector<EntryId> chooseScaleNeighbours(const std::deque<DatabaseEntry>& entries, EntryId match,
                                           const MetricTranslationOptions& options) {
  std::vector<EntryId> out;
  if (match >= entries.size() || !std::isfinite(entries[match].odometer)) return out;
  const double at = entries[match].odometer;
  const std::uint32_t run = entries[match].odometry_run;
  // Odometers never decrease, so each direction stops at the first entry
  // beyond max_baseline_m. The odometer measures the baseline within one
  // odometry run only: across a restart or a mission boundary the next
  // entry may be anywhere.
  for (std::size_t j = match + 1; j < entries.size(); ++j) {
    const double d = entries[j].odometer - at;
    if (entries[j].odometry_run != run || !std::isfinite(d) || d > options.max_baseline_m) break;
    if (d >= options.min_baseline_m) {
      out.push_back(static_cast<EntryId>(j));
      break;
    }
  }
  for (std::size_t j = match; j-- > 0;) {
    const double d = at - entries[j].odometer;
    if (entries[j].odometry_run != run || !std::isfinite(d) || d > options.max_baseline_m) break;
    if (d >= options.min_baseline_m) {
      out.push_back(static_cast<EntryId>(j));
      break;
    }
  }
  return out;
}

MetricTranslation estimateMetricTranslation(const std::vector<Correspondence>& loop_inliers,
                                            const CameraIntrinsics& query_intrinsics,
                                            const VerificationView& match,
                                            const std::vector<ScaleNeighbour>& neighbours,
                                            const CameraIntrinsics& match_intrinsics,
                                            const GeometricVerificationOptions& geometric,
                                            const MetricTranslationOptions& options) {
  using namespace metric_steps;
  MetricTranslation out;
  bool baselines = !neighbours.empty();
  for (const ScaleNeighbour& n : neighbours) {
    baselines = baselines && std::isfinite(n.baseline_m) && n.baseline_m > 0;
  }
  if (!query_intrinsics.valid || !match_intrinsics.valid || !baselines) {
    out.status = MetricTranslationStatus::kNoOdometry;
    return out;
  }
  // RANSAC is the cost: first the correspondences alone say whether enough
  // loop inliers could get a depth.
  const NeighbourCandidates candidates =
      findNeighbourCandidates(loop_inliers, match, neighbours, geometric);
  if (candidates.coverable < options.min_points) {
    out.status = MetricTranslationStatus::kTooFewPoints;
    return out;
  }
  // 1. Each neighbour's pose in M, in metres by the odometer.
  const std::vector<NeighbourTrack> tracks =
      poseNeighbours(candidates, match, neighbours, match_intrinsics, geometric);
  if (tracks.empty()) {
    out.status = MetricTranslationStatus::kNoNeighbourPose;
    return out;
  }
  // 2. The loop inliers the neighbours see, triangulated in M's frame.
  const cv::Matx33d K = metric_geometry::cameraMatrix(match_intrinsics);
  const TriangulatedLoop loop =
      triangulateLoopInliers(loop_inliers, tracks, K, geometric.ransac_threshold_px);
  out.triangulated = static_cast<int>(loop.points.size());
  if (out.triangulated < options.min_points) {
    out.status = MetricTranslationStatus::kTooFewPoints;
    return out;
  }
  // 3. T_Q_M by PnP, refined together with the points' depths.
  LoopPoseFit fit;
  out.status = fitLoopPose(loop, tracks, query_intrinsics, K, geometric, options, &fit);
  out.inliers = fit.inlier_count;
  out.rms_px = fit.rms_px;
  if (out.status != MetricTranslationStatus::kEstimated) return out;
  // 4. Covariance. Most of the error is shared by all points: a neighbour's
  //    pose (its direction, from the essential matrix) bends every depth
  //    the same way, which no residual shows; a bootstrap over every set of
  //    correspondences (deterministic seed) measures it. An estimate that
  //    does not survive half of its resamples is not published.
  std::mt19937 rng(20260101u);
  const std::vector<cv::Vec3d> samples =
      bootstrapTranslations(tracks, fit, query_intrinsics, K, options.covariance_samples, &rng);
  if (static_cast<int>(samples.size()) * 2 < options.covariance_samples || samples.size() < 2) {
    out.status = MetricTranslationStatus::kPerspectiveFailed;
    return out;
  }
  const std::array<double, 9> covariance = translationCovariance(samples, fit, options);
  std::copy(covariance.begin(), covariance.end(), out.covariance);
  cv::Mat Rq;
  cv::Rodrigues(cv::Mat(fit.rvec), Rq);
  for (int r = 0; r < 3; ++r) {
    out.translation[r] = fit.tvec[r];
    for (int c = 0; c < 3; ++c) out.rotation[3 * r + c] = Rq.at<double>(r, c);
  }
  return out;
}

}  // namespace bowg
