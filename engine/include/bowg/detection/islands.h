// Islands (paper Sec. III-D "Islands Matching", after DLoopDetector) and the
// temporal verification over k previous queries.
#pragma once

#include <deque>
#include <limits>
#include <utility>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/detection/detection_options.h"
#include "bowg/detection/odometry_input.h"

namespace bowg {

struct Island {
  EntryId first = 0, last = 0;  ///< id interval [first, last]
  double score = 0;             ///< H = sum of eta over the members (eq. 10)
  EntryId best_entry = 0;       ///< member with the highest eta
  double best_score = 0;
  int size = 0;
  /// Odometers of the first and last entries (NaN when unknown): the
  /// island's place in metres, for TemporalVerificationOptions::
  /// max_island_distance_m. Set by the caller; computeIslands leaves NaN.
  double first_m = std::numeric_limits<double>::quiet_NaN();
  double last_m = std::numeric_limits<double>::quiet_NaN();
};

/// Groups (entry, eta) candidates with eta >= options.min_score into islands:
/// sorted by id, a new island starts where the id gap exceeds
/// max_intra_island_gap; islands smaller than min_island_size are dropped.
/// Returned sorted by score, best first (ties: the more recent island).
std::vector<Island> computeIslands(std::vector<std::pair<EntryId, double>> candidates,
                                   const IslandOptions& options);

/// True when the id intervals of a and b are close: their gap
/// max(a.first, b.first) - min(a.last, b.last) is at most max_distance
/// (overlapping intervals have a gap <= 0).
bool islandsConsistent(const Island& a, const Island& b, int max_distance);

/// The island options a query with `input` applies: min_score raised by
/// images_only_score_margin when it has no odometry, and the recent-exclusion
/// window recent_exclusion_odometer_m (when set) when it has an odometer but
/// no positions. Every other value as in `options`.
IslandOptions islandOptionsFor(const IslandOptions& options, OdometryInput input);

/// One island a query followed, with the length of its chain (consecutive
/// queries with consistent islands ending at it, itself included).
struct IslandHypothesis {
  Island island;
  int chain_length = 0;
};

/// DLoopDetector-style temporal verification: remembers the best island of
/// each previous query; a match is temporally consistent when the islands of
/// the k previous consecutive queries form a chain of consistent islands
/// ending at the current one. With several hypotheses per query
/// (TemporalVerificationOptions::hypotheses) each followed island carries its
/// own chain, extended from any previous hypothesis it is consistent with.
class TemporalConsistency {
 public:
  /// Records the current query's best island and returns whether it is
  /// consistent with the k previous ones (always true for k = 0).
  /// `query_m`: the query's odometer (NaN = unknown); with it, the previous
  /// query's and both islands' odometers, and max_island_distance_m > 0,
  /// consistency is judged in metres: the previous island shifted by the
  /// metres driven between the two queries must come within
  /// max_island_distance_m of this one.
  bool update(const Island& island, const TemporalVerificationOptions& options,
              double query_m = std::numeric_limits<double>::quiet_NaN());
  /// The same with several islands of the query followed: `islands[chosen]`
  /// is the query's island (returned verdict, lastIsland()); every island's
  /// chain is one more than the longest chain of the previous query's
  /// hypotheses it is consistent with (1 when none). The others are kept as
  /// otherHypotheses() for the next query.
  bool update(const std::vector<Island>& islands, std::size_t chosen,
              const TemporalVerificationOptions& options,
              double query_m = std::numeric_limits<double>::quiet_NaN());
  /// A query without an island: the chain survives up to
  /// options.max_missed_queries consecutive ones, then breaks.
  void miss(const TemporalVerificationOptions& options);
  /// Breaks the chain whatever the options (a query that could not be
  /// scored at all, a reset).
  void breakChain();
  void reset() { breakChain(); }
  int chainLength() const { return chain_length_; }
  /// The chain `island` would get from update() now (before it is called):
  /// one more than the longest consistent chain among the previous query's
  /// followed islands (1 when none).
  int chainTo(const Island& island, const TemporalVerificationOptions& options,
              double query_m = std::numeric_limits<double>::quiet_NaN()) const {
    const int longest = longestChainTo(island, options, query_m);
    return longest < std::numeric_limits<int>::max() ? longest + 1 : longest;
  }
  /// Consecutive queries without an island since last_ (0 after update()).
  int missedQueries() const { return missed_; }
  /// For persistence.
  const Island& lastIsland() const { return last_; }
  /// The odometer of the query that recorded lastIsland() (NaN = unknown).
  double lastQueryOdometer() const { return last_query_m_; }
  /// The previous query's followed islands besides lastIsland().
  const std::vector<IslandHypothesis>& otherHypotheses() const { return others_; }
  void restore(const Island& last, int chain_length, int missed_queries = 0,
               double last_query_m = std::numeric_limits<double>::quiet_NaN(),
               std::vector<IslandHypothesis> others = {});

 private:
  /// Whether `previous` (of the previous query) and `current` are the same
  /// place seen by the moving robot.
  bool consistent(const Island& previous, const Island& current,
                  const TemporalVerificationOptions& options, double query_m) const;
  /// The longest chain among the followed islands of the previous query
  /// that `island` is consistent with (0 when none).
  int longestChainTo(const Island& island, const TemporalVerificationOptions& options,
                     double query_m) const;

  std::vector<IslandHypothesis> others_;
  Island last_;
  int chain_length_ = 0;  ///< consecutive consistent queries ending at last_
  int missed_ = 0;        ///< queries without an island since last_
  double last_query_m_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace bowg
