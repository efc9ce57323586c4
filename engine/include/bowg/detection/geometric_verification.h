// Geometric verification of a loop candidate (paper Sec. III-D, after
// DLoopDetector): point correspondences between the query and the candidate
// found through the direct index (features that descend through the same
// vocabulary node at the chosen level), then a fundamental matrix by RANSAC.
//
// Relative pose convention (when intrinsics are known): R and t describe the
// pose of the MATCH camera in the QUERY camera frame, T_Q_M: a point X_M in
// match-camera coordinates is X_Q = R * X_M + t in query-camera coordinates;
// t (unit length) is the direction from the query camera centre to the match
// camera centre, expressed in the query frame (scale unobservable).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "bowg/core/correspondence.h"
#include "bowg/core/types.h"
#include "bowg/detection/detection_options.h"
#include "bowg/detection/loop_status.h"
#include "bowg/vocabulary/bow_vector.h"

namespace bowg {

/// The features of one side of the verification.
struct VerificationView {
  const std::vector<ImagePoint>* points = nullptr;
  const std::vector<Descriptor>* descriptors = nullptr;
  const DirectIndex* direct = nullptr;  ///< unused when matching exhaustively
};

/// (query feature, match feature) index pairs. Only features sharing a
/// direct-index node are compared (all pairs when options.exhaustive); a pair
/// is kept when its Hamming distance is <= max_hamming, it passes the ratio
/// test (best < max_neighbour_ratio * second best among the query feature's
/// candidates, when there is a second) and it is mutual: the query feature is
/// also the closest of the candidates of the match feature (which makes every
/// match feature used at most once). Sorted by query index.
std::vector<std::pair<std::uint32_t, std::uint32_t>> findCorrespondences(
    const VerificationView& query, const VerificationView& match,
    const GeometricVerificationOptions& options);

struct GeometricVerificationResult {
  /// kLoopDetected, kTooFewCorrespondences (< 8) or kTooFewInliers.
  LoopStatus status = LoopStatus::kTooFewCorrespondences;
  int correspondences = 0;
  int inliers = 0;
  std::vector<Correspondence> inlier_correspondences;
  bool has_relative_pose = false;
  double rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  ///< row-major, T_Q_M
  double translation_direction[3] = {0, 0, 0};       ///< unit, T_Q_M
};

/// Correspondences, then a fundamental matrix by RANSAC (fundamentalRansac,
/// or cv::findFundamentalMat(FM_RANSAC) when !options.native_ransac) at
/// ransac_threshold_px and ransac_confidence; a loop when inliers >=
/// min_inliers. With valid `intrinsics` (assumed shared by both images),
/// cv::findEssentialMat + cv::recoverPose on the F inliers give the pose.
GeometricVerificationResult verifyGeometry(const VerificationView& query,
                                           const VerificationView& match,
                                           const CameraIntrinsics& intrinsics,
                                           const GeometricVerificationOptions& options);

/// The same on correspondences already found by findCorrespondences(query,
/// match, options) (the re-ranking counts them before it runs RANSAC).
/// `decisive_inliers`: the inliers a model needs to change the caller's
/// choice when that is more than min_inliers (the re-ranking's best count so
/// far); the RANSAC's sample bound is then computed for it.
GeometricVerificationResult verifyCorrespondences(
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
    const VerificationView& query, const VerificationView& match,
    const CameraIntrinsics& intrinsics, const GeometricVerificationOptions& options,
    int decisive_inliers = 0);

/// OpenCV findFundamentalMat's fixed sample limit (its maxIters default): the
/// RANSAC's limit when its samples are not bounded by the acceptance.
constexpr int kOpenCvRansacSamples = 1000;

/// The fundamental-matrix RANSAC's sample limit when it only has to find a
/// model with `min_inliers` of `correspondences` pairs: OpenCV's adaptive
/// stop at the inlier ratio w = min_inliers / correspondences,
/// round(log(1 - confidence) / log(1 - w^7)) (7-point samples), within
/// [1, 1000] (1,000 is OpenCV's fixed limit). A run that finds such a model
/// stops by then anyway; one that does not cannot accept.
int ransacSampleBound(int correspondences, int min_inliers, double confidence);

/// Whether the verification's RANSAC can be bounded: always with the native
/// RANSAC; with OpenCV's only from 3.4.10 / 4.3, whose findFundamentalMat
/// takes a sample limit (without it ransac_bound_confidence has no effect).
bool ransacSampleBoundAvailable(const GeometricVerificationOptions& options);

/// Relative pose T_Q_M from point pairs (query pixel, match pixel) with the
/// essential matrix: cv::findEssentialMat by RANSAC, its model refitted to
/// the pairs it agrees with (Levenberg-Marquardt on their Sampson distances,
/// as the metric translation's neighbours); false when it cannot be
/// estimated.
bool relativePoseFromCorrespondences(const std::vector<Correspondence>& pairs,
                                     const CameraIntrinsics& intrinsics, double ransac_threshold_px,
                                     double confidence, double rotation[9],
                                     double translation_direction[3]);

}  // namespace bowg
