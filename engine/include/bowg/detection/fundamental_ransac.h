// A fundamental matrix by RANSAC over 7-point samples (the geometric
// verification's model, paper Sec. III-D): the same model, inlier test and
// adaptive stop as OpenCV's findFundamentalMat(FM_RANSAC), without its
// per-sample allocations and SVD, so that a sample costs ~1 us instead of
// ~8 us on a pipe candidate's 50-200 correspondences; and each new best
// model refitted to its inliers, which OpenCV's RANSAC does not do.
#pragma once

#include <cstdint>
#include <vector>

#include "bowg/detection/fundamental_matrix.h"

namespace bowg {

struct FundamentalRansacOptions {
  /// Inlier: epipolarErrorSquared <= threshold^2 (pixels).
  double threshold_px = 2.0;
  /// Adaptive stop: after N samples without an all-inlier sample at the best
  /// model's inlier ratio w, (1 - w^7)^N <= 1 - confidence.
  double confidence = 0.99;
  /// At most this many samples (OpenCV's fixed limit is 1,000).
  int max_samples = 1000;
  /// Least-squares refits of each new best model to its inliers while they
  /// gain inliers (local optimisation); 0 = plain RANSAC, OpenCV's.
  int refits = 3;
  /// The sample generator's seed: the same pairs give the same model.
  std::uint64_t seed = 0x9e3779b97f4a7c15ULL;
};

struct FundamentalRansacResult {
  bool found = false;                         ///< a model with at least 7 inliers
  double f[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};  ///< row-major, pixels
  std::vector<unsigned char> inlier_mask;     ///< per pair; empty when !found
  int inliers = 0;
  int samples = 0;  ///< samples drawn
};

/// RANSAC over `pairs` (at least 7): each sample's 7-point solutions
/// (computed on coordinates normalised per image, Hartley's conditioning)
/// are scored by their inliers in pixels; the model with the most inliers
/// wins (the first of equals), refitted to its inliers (`refits`).
FundamentalRansacResult fundamentalRansac(const std::vector<PointPair>& pairs,
                                          const FundamentalRansacOptions& options);

/// The samples after which a 7-point RANSAC whose best model has inlier
/// ratio w stops at `confidence`: round(log(1 - confidence) / log(1 - w^7))
/// within [1, limit] (OpenCV's RANSACUpdateNumIters, with its rounding).
int adaptiveSampleCount(double inlier_ratio, double confidence, int limit);

}  // namespace bowg
