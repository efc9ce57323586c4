// Metric translation of a loop: the scale two views cannot give, taken from
// the odometry between the match keyframe M and one of its neighbours N.
//
// The essential matrix of a loop fixes the rotation and only the direction
// of the translation (geometric_verification.h). The robot's own odometer
// knows how far it drove from M to a neighbour keyframe N, a few
// centimetres: the essential matrix of M and N (RANSAC, then refitted on all
// its inliers) scaled by that distance triangulates M's features in metres
// (with a neighbour on each side of M, twice as many features have a track);
// the loop's inlier correspondences give those points' pixels in the query
// Q, and a perspective-n-point fit, refined together with the points'
// depths (metric_geometry.h), gives the pose of M in Q's optical frame,
// T_Q_M, with its translation in metres.
//
// What the covariance says (query optical frame, m^2): most of the error is
// shared by all points (the neighbour's pose from the essential matrix bends
// every depth the same way, which no residual shows), so it is measured: a
// bootstrap resamples both sets of correspondences (match-neighbour and
// loop), repeats the estimate and takes the spread of t. Added: a corner's
// pixel accuracy through the fit's Jacobian, and the odometer's error over
// the baseline (every point, and so t, scales with it: a relative error f
// adds (f |t|)^2 along t). docs/pose_graph.md compares it with the error on
// rendered sequences.
//
// The baseline is the path length driven between M and N (the odometer),
// taken as the camera's displacement: exact on straight runs, short by the
// camera's offset from the body times the turn in a bend, which is why N is
// a near neighbour (a few centimetres to decimetres).
#pragma once

#include <deque>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/database/database.h"
#include "bowg/detection/detection_options.h"
#include "bowg/detection/geometric_verification.h"

namespace bowg {

/// Why a metric translation was not estimated (kEstimated when it was).
enum class MetricTranslationStatus {
  kEstimated = 0,
  kDisabled,           ///< MetricTranslationOptions::enabled is false
  kNoOdometry,         ///< odometers or intrinsics unknown
  kNoNeighbour,        ///< no keyframe within [min, max]_baseline_m of the match
  kNoNeighbourPose,    ///< the match shares too few correspondences with every neighbour
  kTooFewPoints,       ///< fewer than min_points triangulated loop inliers
  kPerspectiveFailed,  ///< the PnP fit failed or kept fewer than min_points
  /// The estimate is longer than the odometry allows between the two
  /// keyframes (odometryDistanceBound): a wrong neighbour pose scaled the
  /// points, and a pose graph would take metres for centimetres.
  kOutsideOdometry,
};

const char* toString(MetricTranslationStatus s);

struct MetricTranslation {
  MetricTranslationStatus status = MetricTranslationStatus::kNoOdometry;
  /// T_Q_M (as GeometricVerificationResult): a point X_M in the match camera
  /// is X_Q = R X_M + t; t in metres. Valid when status == kEstimated.
  double rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double translation[3] = {0, 0, 0};
  /// Covariance of `translation`, row-major 3x3, m^2.
  double covariance[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  /// Loop inliers triangulated from M and N, and the PnP fit's inliers among them.
  int triangulated = 0;
  int inliers = 0;
  /// The inliers' RMS reprojection error in the query (px).
  double rms_px = 0;
};

/// A neighbour N of the match M (taken by the same camera) and the metres
/// driven between them (> 0).
struct ScaleNeighbour {
  VerificationView view;
  double baseline_m = 0;
};

/// The estimate from the loop's inlier correspondences (query pixel, match
/// feature index), the match M (`match_intrinsics`) and one or more of its
/// neighbours: each neighbour's points are triangulated at its own metric
/// baseline, all in M's frame, and one PnP fit uses them all. The match and
/// neighbour correspondences are found as the geometric verification finds
/// them (geometric options).
MetricTranslation estimateMetricTranslation(const std::vector<Correspondence>& loop_inliers,
                                            const CameraIntrinsics& query_intrinsics,
                                            const VerificationView& match,
                                            const std::vector<ScaleNeighbour>& neighbours,
                                            const CameraIntrinsics& match_intrinsics,
                                            const GeometricVerificationOptions& geometric,
                                            const MetricTranslationOptions& options);

/// The neighbours of database entry `match` to take baselines from: the
/// nearest entry after it and the nearest before it whose odometer differs
/// from the match's by at least min_baseline_m and at most max_baseline_m
/// (after first; none when the match's odometer is unknown), in the match's
/// odometry run (another run's odometer is no baseline: a restart, another
/// mission).
std::vector<EntryId> chooseScaleNeighbours(const std::deque<DatabaseEntry>& entries, EntryId match,
                                           const MetricTranslationOptions& options);

}  // namespace bowg
