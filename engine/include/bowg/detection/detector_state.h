// The loop detector's memory of previous queries (eq. 7's previous scores,
// the temporal-verification chains, the normaliser history): everything
// besides the database that a restarted detector needs to continue where it
// stopped. Saved with the database (detector_file.h).
#pragma once

#include <limits>
#include <utility>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/detection/islands.h"
#include "bowg/detection/odometry_gate.h"
#include "bowg/detection/place_links.h"
#include "bowg/detection/verified_chain.h"
#include "bowg/scoring/normaliser_history.h"

namespace bowg {

/// The LoopDetector's memory of previous queries, saved with the database.
struct DetectorState {
  /// The previous query's final eta per scored entry (eq. 7's eta(t-1, .)),
  /// sorted by entry id.
  std::vector<std::pair<EntryId, double>> previous_etas;
  /// Queries since previous_etas were set that could not be scored
  /// (temporal_score.max_missed_queries, temporal_alignment.h).
  int missed_queries = 0;
  /// Odometer of the query previous_etas belong to (NaN = unknown).
  double previous_odometer = std::numeric_limits<double>::quiet_NaN();
  /// The temporal-verification chain (Sec. III-D).
  TemporalConsistency consistency;
  /// Recent s(I_t, I_t-1), for the normaliser floor (normaliser_history.h).
  NormaliserHistory normalisers;
  /// Entries joined by accepted loops (TemporalVerificationOptions::
  /// linked_places); recorded whether or not the option is on.
  PlaceLinks place_links;
  /// The odometry run new entries belong to (DatabaseEntry::odometry_run):
  /// a robot restarted with a saved database has a new odometry frame, so
  /// LoopDetector::load starts a new run.
  std::uint32_t odometry_run = 0;
  /// The mission new entries belong to (DatabaseEntry::mission; one of the
  /// database's missions()).
  std::uint32_t mission = 0;
  /// The last kLoopAnchors accepted loops, oldest first
  /// (IslandOptions::odometry_anchor_m); recorded whether or not the option
  /// is on. Not saved (LoopAnchor).
  std::vector<LoopAnchor> recent_loops;
  VerifiedChain verified_chain;
};

}  // namespace bowg
