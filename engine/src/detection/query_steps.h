// One query of the loop detector once the query's vectors are ready (paper
// Fig. 2 after the word groups): normalisers and candidate scores (eqs. 2-5,
// 9), the temporal score (eqs. 6-7), islands (eq. 10), temporal and geometric
// verification (Sec. III-D). Internal to the detection stage; LoopDetector::
// process() (loop_detector.cpp) prepares the query and stores the keyframe.
#pragma once

#include <chrono>
#include <vector>

#include "bowg/database/database.h"
#include "bowg/detection/detector_state.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "detection/verifier.h"

namespace bowg {
namespace query_steps {

using Clock = std::chrono::steady_clock;

inline double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

/// What a query reads and updates besides its own keyframe.
struct QueryContext {
  const Vocabulary& vocabulary;
  const LoopDetectorOptions& options;
  const Database& database;
  DetectorState& state;
  std::vector<CandidateScores>& candidates;  ///< the query's, sorted by entry id
  EntryViewCache& views;                     ///< recent entries' views, across queries
};

// A query that cannot be scored (no features, database too small, normaliser
// too small, no candidate): eq. 7's previous scores survive up to
// temporal_score.max_missed_queries such queries and the temporal chain up to
// temporal_verification.max_missed_queries (0 = the paper: forgotten at once).
void recordUnscoredQuery(const LoopDetectorOptions& options, DetectorState* state);

/// Runs the query of `query_entry` (not yet in the database) and fills `r`:
/// status, scores, the chosen island, the match and its geometry, timings.
void runQuery(const QueryContext& ctx, const DatabaseQuery& q, const DatabaseEntry& query_entry,
              const CameraIntrinsics& intrinsics, bool with_groups, bool with_distribution,
              LoopResult* r);

}  // namespace query_steps
}  // namespace bowg
