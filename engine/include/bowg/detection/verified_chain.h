// The verified chain (VerifiedChainOptions): a loop that no odometry position
// places must continue the geometrically verified matches of the previous
// queries. In a pipe that repeats every section, a look-alike passes every
// check of one query (scores, islands, tens of RANSAC inliers) and its
// island even follows the robot from query to query. What changes from query
// to query is which look-alike wins the geometric re-ranking, since every
// section offset fits the repeated texture about as well, and a look-alike
// has few inliers on what the pipe does not repeat. The true place wins
// query after query with inliers on its own marks and grain.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/detection/detection_options.h"
#include "bowg/detection/place_links.h"

namespace bowg {

/// A verified match of one query: a database entry with at least
/// min_inliers RANSAC inliers.
struct ChainMatch {
  EntryId entry = 0;
  /// Inliers on query features the recent past does not repeat
  /// (repeated_texture.h); -1 when not counted.
  int unique_inliers = -1;
};

/// One query's outcome for the chain: its id, odometer (NaN = unknown) and
/// up to two verified matches, the re-ranking's best first.
struct ChainQuery {
  EntryId query = 0;
  double odometer = 0;
  std::uint8_t matches = 0;  ///< how many of `match` are valid
  ChainMatch match[2];
  bool published = false;  ///< match[0] was published as a loop
  void add(const ChainMatch& m) {
    if (matches < 2) match[matches++] = m;
  }
};

/// What a chain step compares besides the two queries: the odometer of
/// every database entry (Database::odometers) and the places joined by
/// published loops.
struct ChainContext {
  const std::vector<double>& entry_odometers;
  const PlaceLinks& links;
  const TemporalVerificationOptions&
      temporal;      ///< max_island_distance_m, linked_places, min_step_m
  double drift = 0;  ///< relative odometer error between the passes (odometry_gate_drift)
  /// The odometry gate judged the loop's match (odometryGateApplies): every
  /// look-alike farther than its radius is out, so the chain's unique
  /// inliers count on average (VerifiedChain::passes).
  bool position_gated = false;
};

/// Whether `next`'s match follows `previous`'s as the robot moved from the
/// previous query to the next. In metres when all four odometers are known:
/// the match moved as far as the query, within max_island_distance_m, plus
/// `drift` of the metres driven, plus half the wider gap from each match to
/// its neighbouring entries (each at most max_island_distance_m): a query
/// between two keyframes of a sparse pass matches either. Else in keyframe
/// ids: the match advanced by between half and twice the query's step (a
/// speed ratio of at most 2 between the passes), plus or minus one
/// keyframe. With linked_places the same test is also made between the
/// places' first entries (PlaceLinks::root): on a circuit's later laps the
/// re-ranking's match jumps between the laps it has seen, which published
/// loops join into one place.
bool chainStep(EntryId previous_query, double previous_odometer, EntryId previous_match,
               EntryId next_query, double next_odometer, EntryId next_match,
               const ChainContext& context);

class VerifiedChain {
 public:
  /// Records a query's outcome (queries in increasing id order); the chain
  /// remembers the last 64.
  void push(const ChainQuery& q);
  /// Whether `current`'s first match passes the chain: walking back from it,
  /// each previous query has a verified match that chainStep follows to the
  /// last one taken (preferring one with min_unique_inliers), queries
  /// without any are skipped up to options.max_missed in a row, and a query
  /// whose matches all fail (a stray) is skipped too, up to
  /// options.max_strays in all (each counting towards max_missed); the next
  /// one ends the walk. The step across strays is chainStep's and, where it
  /// is in keyframe ids, also at the rate the walk's matches advanced per
  /// query since `current` (measured over two queries or more), within 1.5
  /// keyframes: chainStep's band in ids widens with every query stepped
  /// over.
  /// Passes when the walk reaches a published loop, or when it takes
  /// options.length matches, counted only once the robot drove min_step_m
  /// since the last one counted, all of which (and the current) have
  /// min_unique_inliers; with context.position_gated, min_unique_inliers on
  /// average and each at least half of it (rounded down). Always false for
  /// a query without a match.
  bool passes(const ChainQuery& current, const VerifiedChainOptions& options,
              const ChainContext& context) const;
  void clear() { recent_.clear(); }
  std::size_t size() const { return recent_.size(); }

 private:
  std::deque<ChainQuery> recent_;
};

}  // namespace bowg
