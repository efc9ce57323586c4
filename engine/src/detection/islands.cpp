// Islands (paper Sec. III-D "Islands Matching", eq. 10) and the temporal
// verification, after DLoopDetector (Galvez-Lopez & Tardos, T-RO 2012).
//
// Where this file departs from DLoopDetector's TemplatedLoopDetector, it
// follows the agreed header (bowg/detection/islands.h, detection_options.h):
//  - ids a and b join one island when b - a <= max_intra_island_gap
//    (DLoopDetector: b - a < max_intragroup_gap);
//  - min_island_size counts the members above the threshold
//    (DLoopDetector: the id span last - first + 1);
//  - ties are broken towards the more recent island / entry.
// The temporal chain rule is DLoopDetector's (see TemporalConsistency::update).
#include "bowg/detection/islands.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace bowg {

IslandOptions islandOptionsFor(const IslandOptions& options, OdometryInput input) {
  IslandOptions applied = options;
  if (input == OdometryInput::kNone) applied.min_score += options.images_only_score_margin;
  if (input == OdometryInput::kOdometer && options.recent_exclusion_odometer_m > 0.0) {
    applied.recent_exclusion_m = options.recent_exclusion_odometer_m;
  }
  return applied;
}

std::vector<Island> computeIslands(std::vector<std::pair<EntryId, double>> candidates,
                                   const IslandOptions& options) {
  options.validate();
  // Keep candidates with eta >= min_score (NaN scores fail the test).
  candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                  [&options](const std::pair<EntryId, double>& c) {
                                    return !(c.second >= options.min_score);
                                  }),
                   candidates.end());
  std::sort(candidates.begin(), candidates.end(),
            [](const std::pair<EntryId, double>& a, const std::pair<EntryId, double>& b) {
              return a.first < b.first;
            });

  std::vector<Island> islands;
  const auto close_island = [&islands, &options](const Island& island) {
    if (island.size >= options.min_island_size) islands.push_back(island);
  };
  Island current;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const EntryId id = candidates[i].first;
    const double eta = candidates[i].second;
    if (i > 0 && id == current.last) {
      throw std::invalid_argument("computeIslands: entry " + std::to_string(id) +
                                  " appears twice among the candidates");
    }
    const bool starts_new =
        i == 0 || static_cast<std::int64_t>(id) - static_cast<std::int64_t>(current.last) >
                      options.max_intra_island_gap;
    if (starts_new) {
      if (i > 0) close_island(current);
      current = Island();
      current.first = id;
      current.best_entry = id;
      current.best_score = eta;
    }
    current.last = id;
    current.score += eta;  // eq. 10: H = sum of eta over the island
    ++current.size;
    if (eta >= current.best_score) {  // ties: the more recent entry
      current.best_score = eta;
      current.best_entry = id;
    }
  }
  if (!candidates.empty()) close_island(current);

  // Best first; islands are disjoint, so "more recent" = larger first id.
  std::sort(islands.begin(), islands.end(), [](const Island& a, const Island& b) {
    if (a.score != b.score) return a.score > b.score;
    return a.first > b.first;
  });
  return islands;
}

bool islandsConsistent(const Island& a, const Island& b, int max_distance) {
  const std::int64_t gap = static_cast<std::int64_t>(std::max(a.first, b.first)) -
                           static_cast<std::int64_t>(std::min(a.last, b.last));
  return gap <= max_distance;
}

namespace {

bool finiteExtent(const Island& i) { return std::isfinite(i.first_m) && std::isfinite(i.last_m); }

}  // namespace

bool TemporalConsistency::consistent(const Island& previous, const Island& current,
                                     const TemporalVerificationOptions& options,
                                     double query_m) const {
  if (options.max_island_distance_m > 0.0 && std::isfinite(query_m) &&
      std::isfinite(last_query_m_) && finiteExtent(previous) && finiteExtent(current)) {
    const double driven = query_m - last_query_m_;
    const double gap = std::max(current.first_m, previous.first_m + driven) -
                       std::min(current.last_m, previous.last_m + driven);
    return gap <= options.max_island_distance_m;
  }
  const int distance = options.max_island_distance * (1 + missed_);
  return islandsConsistent(previous, current, distance);
}

int TemporalConsistency::longestChainTo(const Island& island,
                                        const TemporalVerificationOptions& options,
                                        double query_m) const {
  if (chain_length_ == 0) return 0;
  int longest = consistent(last_, island, options, query_m) ? chain_length_ : 0;
  for (const IslandHypothesis& h : others_) {
    if (h.chain_length > longest && consistent(h.island, island, options, query_m)) {
      longest = h.chain_length;
    }
  }
  return longest;
}

bool TemporalConsistency::update(const Island& island, const TemporalVerificationOptions& options,
                                 double query_m) {
  return update(std::vector<Island>{island}, 0, options, query_m);
}

bool TemporalConsistency::update(const std::vector<Island>& islands, std::size_t chosen,
                                 const TemporalVerificationOptions& options, double query_m) {
  options.validate();
  if (chosen >= islands.size()) {
    throw std::invalid_argument("TemporalConsistency::update: chosen island " +
                                std::to_string(chosen) + " of " + std::to_string(islands.size()));
  }
  // DLoopDetector's updateTemporalWindow: the chain counts the queries whose
  // best islands were pairwise consistent with their predecessor, including
  // the current one. It restarts at 1 when the new island is not consistent
  // with the last one (or after breakChain()), and a match passes when the
  // chain is longer than k, i.e. the current island and the islands of the k
  // previous consecutive queries form one chain. k = 0 always passes.
  //
  // Queries without an island in between (miss(), at most max_missed_queries
  // of them) neither break nor extend the chain; the place moved on during
  // them, so the allowed distance grows with their number.
  //
  // In metres (max_island_distance_m, odometers known): the previous island
  // moves with the robot by the metres driven since its query; the
  // distance travelled already covers any missed queries in between.
  //
  // Several hypotheses: every followed island of this query takes the
  // longest consistent chain among the previous query's followed islands.
  //
  // A query driven less than min_step_m after the last counted one (a robot
  // standing still) is the same view again: it passes when the chain it
  // continues passed already, and leaves the state as it is, so that the
  // next query is judged against the last counted one with the metres
  // driven since.
  if (options.min_step_m > 0.0 && chain_length_ > 0 && std::isfinite(query_m) &&
      std::isfinite(last_query_m_) && query_m - last_query_m_ < options.min_step_m) {
    return options.k == 0 || longestChainTo(islands[chosen], options, query_m) > options.k;
  }
  std::vector<IslandHypothesis> next(islands.size());
  for (std::size_t i = 0; i < islands.size(); ++i) {
    const int longest = longestChainTo(islands[i], options, query_m);
    next[i].island = islands[i];
    next[i].chain_length = longest < std::numeric_limits<int>::max() ? longest + 1 : longest;
  }
  last_ = next[chosen].island;
  chain_length_ = next[chosen].chain_length;
  next.erase(next.begin() + static_cast<std::ptrdiff_t>(chosen));
  others_ = std::move(next);
  last_query_m_ = query_m;
  missed_ = 0;
  return chain_length_ > options.k;
}

void TemporalConsistency::miss(const TemporalVerificationOptions& options) {
  options.validate();
  if (chain_length_ == 0) return;
  if (missed_ < options.max_missed_queries) {
    ++missed_;
  } else {
    breakChain();
  }
}

void TemporalConsistency::breakChain() {
  // DLoopDetector restarts its window when a query is further than
  // max_distance_between_queries from the last matched one; here the caller
  // breaks the chain on every query that yields no island.
  last_ = Island();
  others_.clear();
  chain_length_ = 0;
  missed_ = 0;
  last_query_m_ = std::numeric_limits<double>::quiet_NaN();
}

void TemporalConsistency::restore(const Island& last, int chain_length, int missed_queries,
                                  double last_query_m, std::vector<IslandHypothesis> others) {
  if (chain_length < 0) {
    throw std::invalid_argument("TemporalConsistency::restore: chain_length must be >= 0 (got " +
                                std::to_string(chain_length) + ")");
  }
  if (chain_length > 0 && last.first > last.last) {
    throw std::invalid_argument("TemporalConsistency::restore: island first " +
                                std::to_string(last.first) + " > last " +
                                std::to_string(last.last));
  }
  if (missed_queries < 0 || (chain_length == 0 && missed_queries != 0)) {
    throw std::invalid_argument("TemporalConsistency::restore: missed_queries " +
                                std::to_string(missed_queries) +
                                " is negative or set without a chain");
  }
  for (const IslandHypothesis& h : others) {
    if (chain_length == 0 || h.chain_length < 1 || h.island.first > h.island.last) {
      throw std::invalid_argument(
          "TemporalConsistency::restore: a hypothesis without a chain, with a chain < 1 or "
          "with first > last");
    }
  }
  others_ = std::move(others);
  last_ = chain_length > 0 ? last : Island();
  chain_length_ = chain_length;
  missed_ = missed_queries;
  last_query_m_ = chain_length > 0 ? last_query_m : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace bowg
