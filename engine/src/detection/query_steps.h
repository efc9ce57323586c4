// One query of the loop detector once the query's vectors are ready (paper
// Fig. 2 after the word groups), as a list of stages: candidate scores
// (eqs. 2-7, 9; candidate_scoring.h), the odometry gates
// (candidate_gates.h), islands (eq. 10) and their geometric re-ranking
// (island_choice.h), temporal verification (Sec. III-D; temporal_check.h)
// or the verified chain (chain_query.h), geometric verification
// (match_verification.h). Internal to the detection stage;
// LoopDetector::process() (loop_detector.cpp) prepares the query and stores
// the keyframe.
#pragma once

#include "detection/candidate_scoring.h"
#include "detection/query_context.h"

namespace bowg {
namespace query_steps {

/// Runs the query of `query_entry` (not yet in the database) and fills `r`:
/// status, scores, the chosen island, the match and its geometry, timings.
void runQuery(const QueryContext& ctx, const DatabaseQuery& q, const DatabaseEntry& query_entry,
              const CameraIntrinsics& intrinsics, bool with_groups, bool with_distribution,
              LoopResult* r);

}  // namespace query_steps
}  // namespace bowg
