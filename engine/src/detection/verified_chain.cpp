#include "bowg/detection/verified_chain.h"

#include <algorithm>
#include <cmath>

namespace bowg {
namespace {

// The walk never goes further back than this: length matches with up to
// max_missed skipped queries between them, and the queries of a robot
// standing still.
constexpr std::size_t kRemembered = 64;

// How far the place that match `e` stands for may lie from `e`'s own
// odometer: half the wider gap to its neighbouring entries. A query between
// two keyframes of a sparse pass (15 cm apart) matches either of them, so
// the matches of two queries can be a keyframe further apart or nearer
// than the queries are. At most `cap` (a gap across a reset or a lost
// stretch says nothing of the spacing); 0 where no neighbour's odometer is
// known.
double placeUncertainty(EntryId e, const std::vector<double>& odometers, double cap) {
  double gap = 0.0;
  if (e > 0 && std::isfinite(odometers[e - 1])) gap = std::fabs(odometers[e] - odometers[e - 1]);
  if (e + 1 < odometers.size() && std::isfinite(odometers[e + 1])) {
    gap = std::max(gap, std::fabs(odometers[e + 1] - odometers[e]));
  }
  return std::min(0.5 * gap, cap);
}

// Whether a step between two queries and their matches is measured in
// metres: the chain has a distance tolerance and all four odometers are
// known. Else it is measured in keyframe ids.
bool stepInMetres(double previous_odometer, EntryId previous_match, double next_odometer,
                  EntryId next_match, const ChainContext& c) {
  return c.temporal.max_island_distance_m > 0.0 && std::isfinite(previous_odometer) &&
         std::isfinite(next_odometer) && std::isfinite(c.entry_odometers[previous_match]) &&
         std::isfinite(c.entry_odometers[next_match]);
}

// chainStep without the place links.
bool directStep(EntryId previous_query, double previous_odometer, EntryId previous_match,
                EntryId next_query, double next_odometer, EntryId next_match,
                const ChainContext& c) {
  const TemporalVerificationOptions& tv = c.temporal;
  if (stepInMetres(previous_odometer, previous_match, next_odometer, next_match, c)) {
    const double previous_match_m = c.entry_odometers[previous_match];
    const double next_match_m = c.entry_odometers[next_match];
    const double driven = next_odometer - previous_odometer;
    const double moved = next_match_m - previous_match_m;
    const double tolerance = tv.max_island_distance_m;
    const double spacing = placeUncertainty(previous_match, c.entry_odometers, tolerance) +
                           placeUncertainty(next_match, c.entry_odometers, tolerance);
    return std::fabs(moved - driven) <= tolerance + spacing + c.drift * std::fabs(driven);
  }
  const double steps = static_cast<double>(next_query) - static_cast<double>(previous_query);
  const double advanced = static_cast<double>(next_match) - static_cast<double>(previous_match);
  return advanced >= 0.5 * steps - 1.0 && advanced <= 2.0 * steps + 1.0;
}

// Whether `m` has the unique inliers the chain asks for (any when it asks
// for none).
bool uniqueEnough(const ChainMatch& m, int min_unique) {
  return min_unique <= 0 || m.unique_inliers >= min_unique;
}

// The unique inliers of the matches a chain took (the loop's included).
struct UniqueTally {
  int sum = 0, least = 0, count = 0;
  void add(const ChainMatch& m) {
    least = count == 0 ? m.unique_inliers : std::min(least, m.unique_inliers);
    sum += m.unique_inliers;
    ++count;
  }
  // Each has min_unique; or, on_average, min_unique on average and each
  // at least half of it (rounded down).
  bool enough(int min_unique, bool on_average) const {
    if (min_unique <= 0) return true;
    if (!on_average) return least >= min_unique;
    return least >= min_unique / 2 && sum >= min_unique * count;
  }
};

// The match of `q` that chainStep follows to `last` (preferring one with
// enough unique inliers); nullptr when none does.
const ChainMatch* followingMatch(const ChainQuery& q, const ChainQuery& last, int min_unique,
                                 const ChainContext& c) {
  const ChainMatch* found = nullptr;
  for (std::uint8_t i = 0; i < q.matches; ++i) {
    const ChainMatch& m = q.match[i];
    if (!chainStep(q.query, q.odometer, m.entry, last.query, last.odometer, last.match[0].entry,
                   c)) {
      continue;
    }
    if (found == nullptr || (!uniqueEnough(*found, min_unique) && uniqueEnough(m, min_unique))) {
      found = &m;
    }
  }
  return found;
}

// A step in keyframe ids across stepped-over queries, from `previous`'s
// match `entry` to `last`'s: the match must advance as the walk's matches
// advanced per query from `last` back to `current`'s, within 1.5 keyframes,
// where chainStep's band (half to twice the queries' step) would widen with
// every query stepped over. The rate needs two queries or more behind it.
bool bridgesInIds(const ChainQuery& current, const ChainQuery& last, EntryId previous,
                  EntryId entry) {
  const double measured_queries =
      static_cast<double>(current.query) - static_cast<double>(last.query);
  if (measured_queries < 2.0) return false;
  const double rate =
      (static_cast<double>(current.match[0].entry) - static_cast<double>(last.match[0].entry)) /
      measured_queries;
  const double steps = static_cast<double>(last.query) - static_cast<double>(previous);
  const double advanced = static_cast<double>(last.match[0].entry) - static_cast<double>(entry);
  return std::fabs(advanced - rate * steps) <= 1.5;
}

}  // namespace

bool chainStep(EntryId previous_query, double previous_odometer, EntryId previous_match,
               EntryId next_query, double next_odometer, EntryId next_match,
               const ChainContext& context) {
  if (directStep(previous_query, previous_odometer, previous_match, next_query, next_odometer,
                 next_match, context)) {
    return true;
  }
  if (!context.temporal.linked_places) return false;
  const EntryId previous_place = context.links.root(previous_match);
  const EntryId next_place = context.links.root(next_match);
  if (previous_place == previous_match && next_place == next_match) return false;
  return directStep(previous_query, previous_odometer, previous_place, next_query, next_odometer,
                    next_place, context);
}

void VerifiedChain::push(const ChainQuery& q) {
  recent_.push_back(q);
  if (recent_.size() > kRemembered) recent_.pop_front();
}

bool VerifiedChain::passes(const ChainQuery& current, const VerifiedChainOptions& options,
                           const ChainContext& context) const {
  if (current.matches == 0) return false;
  const int min_unique = options.min_unique_inliers;
  UniqueTally unique;
  unique.add(current.match[0]);
  int length = 0, missed = 0, strays = 0;
  // Whether the walk stepped over a stray since the last match it took.
  bool bridging = false;
  // The last query taken, its match taken in front.
  ChainQuery last = current;
  last.matches = 1;
  const double min_step = context.temporal.min_step_m;
  for (auto it = recent_.rbegin(); it != recent_.rend() && length < options.length; ++it) {
    if (it->matches == 0) {
      if (++missed > options.max_missed) return false;
      continue;
    }
    const ChainMatch* m = followingMatch(*it, last, min_unique, context);
    if (m == nullptr) {
      // A look-alike won this query: stepped over like a query without a
      // match, while the chain allows strays.
      if (++strays > options.max_strays || ++missed > options.max_missed) return false;
      bridging = true;
      continue;
    }
    // Across strays a step in metres keeps its tolerance; in keyframe ids
    // the advance a step admits widens with every query stepped over (one
    // query: -0.5 to 3 keyframes; two: 0 to 5), and so does the room for a
    // look-alike: there the match must advance at the walk's own rate.
    if (bridging &&
        !stepInMetres(it->odometer, m->entry, last.odometer, last.match[0].entry, context) &&
        !bridgesInIds(current, last, it->query, m->entry)) {
      return false;
    }
    bridging = false;
    missed = 0;
    if (it->published && m == &it->match[0]) return true;  // continues a published loop
    // A robot standing still sends one view again and again: one piece of
    // evidence.
    if (min_step > 0.0 && std::isfinite(it->odometer) && std::isfinite(last.odometer) &&
        last.odometer - it->odometer < min_step) {
      continue;
    }
    unique.add(*m);
    ++length;
    last = *it;
    last.match[0] = *m;
    last.matches = 1;
  }
  return length >= options.length && unique.enough(min_unique, context.position_gated);
}

}  // namespace bowg
