// Why a keyframe did or did not yield a loop: the outcome of one query, shared
// by the detector and the geometric verification that decides its last step.
#pragma once

namespace bowg {

/// Why a keyframe did or did not yield a loop (cf. DLoopDetector's
/// DetectionStatus). Exactly one per keyframe.
enum class LoopStatus {
  kLoopDetected = 0,
  kNoFeatures,             ///< the keyframe has no features: added, not queried
  kDatabaseTooSmall,       ///< nothing older than the recent-exclusion window
  kLowNormaliser,          ///< score against the previous keyframe too small
  kNoCandidates,           ///< no database entry shares a word or group
  kNoScoreAboveThreshold,  ///< no candidate reached islands.min_score
  kNoTemporalConsistency,  ///< best island not consistent with k previous
  kTooFewCorrespondences,  ///< fewer than 8 correspondences for RANSAC
  kTooFewInliers,          ///< RANSAC found fewer than min_inliers
  kNoVerifiedChain,        ///< the match does not continue the previous queries' verified matches
};
const char* toString(LoopStatus s);

}  // namespace bowg
