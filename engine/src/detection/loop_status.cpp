#include "bowg/detection/loop_status.h"

namespace bowg {

const char* toString(LoopStatus s) {
  switch (s) {
    case LoopStatus::kLoopDetected:
      return "loop_detected";
    case LoopStatus::kNoFeatures:
      return "no_features";
    case LoopStatus::kDatabaseTooSmall:
      return "database_too_small";
    case LoopStatus::kLowNormaliser:
      return "low_normaliser";
    case LoopStatus::kNoCandidates:
      return "no_candidates";
    case LoopStatus::kNoScoreAboveThreshold:
      return "no_score_above_threshold";
    case LoopStatus::kNoTemporalConsistency:
      return "no_temporal_consistency";
    case LoopStatus::kTooFewCorrespondences:
      return "too_few_correspondences";
    case LoopStatus::kTooFewInliers:
      return "too_few_inliers";
    case LoopStatus::kNoVerifiedChain:
      return "no_verified_chain";
  }
  return "unknown";
}

}  // namespace bowg
