// What every stage of a query reads and updates (query_steps.h runs them):
// the vocabulary, the options, the database, the detector's state across
// queries, and the query's own candidate scores. Internal to the detection
// stage.
#pragma once

#include <chrono>
#include <vector>

#include "bowg/database/database.h"
#include "bowg/database/query_scratch.h"
#include "bowg/detection/detector_state.h"
#include "bowg/detection/islands.h"
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
  QueryScratch& scratch;                     ///< the database query's working memory
  /// options.islands as this query's odometry applies them
  /// (islandOptionsFor): its threshold and recent-exclusion window. The
  /// scoring, the gates' count and the islands read these; the other
  /// stages' island fields do not depend on the odometry.
  const IslandOptions& islands;
};

}  // namespace query_steps
}  // namespace bowg
