// Candidate scoring (candidate_scoring.h): the normalisers against I_{t-1},
// the recent-exclusion window, the database query, eqs. 6-7.
#include "detection/candidate_scoring.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bowg/detection/islands.h"
#include "bowg/scoring/similarity.h"
#include "bowg/scoring/temporal_alignment.h"

namespace bowg {
namespace query_steps {
namespace {

// The number of entries driven up to `odometer`: those whose odometer (an
// entry without one carries the one before it, Database::odometers) is at
// most it. One binary search over the non-decreasing odometers.
std::size_t entriesDrivenUpTo(const Database& database, double odometer) {
  const std::vector<double>& odometers = database.odometers();
  return static_cast<std::size_t>(std::upper_bound(odometers.begin(), odometers.end(), odometer) -
                                  odometers.begin());
}

// Entries with id < the returned limit may be candidates. In keyframes: all
// but the `recent_exclusion` newest. In metres (the query has an odometer and
// recent_exclusion_m > 0): the entries before the newest one driven at least
// recent_exclusion_m before the query; entries without an odometer there are
// treated as recent.
EntryId candidateLimit(const Database& database, const IslandOptions& options, double odometer) {
  const std::size_t n = database.size();
  if (std::isnan(odometer) || !(options.recent_exclusion_m > 0.0)) {
    const std::size_t excluded = static_cast<std::size_t>(options.recent_exclusion);
    return static_cast<EntryId>(n > excluded ? n - excluded : 0);
  }
  // The non-decreasing odometers find the entries driven far enough back;
  // those at the end of that range without an odometer of their own carry
  // the one before them and are dropped.
  std::size_t limit = entriesDrivenUpTo(database, odometer - options.recent_exclusion_m);
  while (limit > 0 && std::isnan(database.entries()[limit - 1].odometer)) --limit;
  return static_cast<EntryId>(limit);
}

// The normalisers' I_{t-1} (SimilarityOptions::normaliser_distance_m): the
// newest entry driven at least that far before the query, when both have
// odometers; else the previous keyframe (the paper).
EntryId normaliserEntry(const Database& database, const SimilarityOptions& options,
                        double odometer) {
  const EntryId previous = static_cast<EntryId>(database.size() - 1);
  if (std::isnan(odometer) || !(options.normaliser_distance_m > 0.0)) return previous;
  const std::size_t behind = entriesDrivenUpTo(database, odometer - options.normaliser_distance_m);
  if (behind == 0 || std::isnan(database.entries()[behind - 1].odometer)) return previous;
  return static_cast<EntryId>(behind - 1);
}

// Without odometry (SimilarityOptions::normaliser_lookback), where the
// query looks normaliser_lookback_ratio times more like I_{t-1} than the
// median previous keyframe did (the robot slowed down or stopped): the
// scores against the newest of the last normaliser_lookback entries that
// looks no more like it than that median (`usual_word`), the view one
// keyframe spacing at the robot's usual speed gives; none (the robot stands
// still): `previous` unchanged.
EntryScores lookBackNormaliser(const Database& database, const DatabaseQuery& q,
                               const SimilarityOptions& options, double odometer,
                               const EntryScores& previous, double usual_word) {
  if (!std::isnan(odometer) || !(usual_word > 0.0) ||
      previous.s_w <= options.normaliser_lookback_ratio * usual_word) {
    return previous;
  }
  const std::size_t n = database.size();
  const std::size_t back = std::min(static_cast<std::size_t>(options.normaliser_lookback), n);
  for (std::size_t k = 2; k <= back; ++k) {
    const EntryScores s = database.score(q, static_cast<EntryId>(n - k));
    if (s.s_w <= usual_word) return s;
  }
  return previous;
}

// True when a normaliser of an enabled component is 0 or below its minimum.
bool lowNormaliser(const Normalisers& tested, const SimilarityOptions& so, bool with_groups,
                   bool with_distribution) {
  const auto low = [](double normaliser, double minimum) {
    return !(normaliser > 0.0) || normaliser < minimum;
  };
  return low(tested.word, so.min_word_normaliser) ||
         (with_groups && low(tested.group, so.min_group_normaliser)) ||
         (with_distribution && low(tested.distribution, so.min_distribution_normaliser));
}

// Eqs. 2, 4, 5 and 6-7 for every scored entry, in ascending entry order,
// into ctx.candidates and etas.
void finalScores(const QueryContext& ctx, const std::vector<EntryScores>& scores,
                 const Normalisers& divisor, bool with_groups, bool with_distribution,
                 double odometer, std::vector<std::pair<EntryId, double>>* etas) {
  const LoopDetectorOptions& options = ctx.options;
  const DetectorState& state = ctx.state;
  etas->reserve(scores.size());
  // Eq. 7's predecessor in metres when odometry allows it
  // (TemporalScoreOptions::alignment_window_m), else in keyframes.
  const TemporalScoreOptions& to = options.temporal_score;
  const bool metric_alignment =
      to.alignment_window_m > 0.0 && !std::isnan(odometer) && !std::isnan(state.previous_odometer);
  const double driven = metric_alignment ? odometer - state.previous_odometer : 0.0;
  ctx.candidates.reserve(scores.size());
  // The scores come in ascending entry order: one forward walk of the
  // temporal memory for all of them.
  AlignedPreviousScores aligned =
      metric_alignment ? AlignedPreviousScores(state.previous_etas, ctx.database.odometers(),
                                               driven, to.alignment_window_m)
                       : AlignedPreviousScores(state.previous_etas, state.missed_queries, to);
  // The options are checked once per query, each candidate's score once.
  const CandidateScoreCombiner combine(options.word_groups, options.distribution,
                                       options.similarity, options.temporal_score);
  for (const EntryScores& s : scores) {
    CandidateScores c;
    c.entry = s.entry;
    c.eta_w = normaliseScore(s.s_w, divisor.word);
    c.eta_g = with_groups ? normaliseScore(s.s_g, divisor.group) : 0.0;
    c.eta_d = with_distribution ? normaliseScore(s.s_d, divisor.distribution) : 0.0;
    c.eta_sim = combine.similarity(c.eta_w, c.eta_g, c.eta_d);
    // Eqs. 6-7: eta(t-1, tj-1) is the previous query's final score of the
    // entry before this one (alignment_window 0), or the best-aligned one
    // near it (temporal_alignment.h); 0 when none was scored then.
    c.eta = combine.temporal(c.eta_sim, aligned(s.entry), c.entry);
    ctx.candidates.push_back(c);
    etas->emplace_back(c.entry, c.eta);
  }
}

}  // namespace

void recordUnscoredQuery(const LoopDetectorOptions& options, DetectorState* state) {
  if (state->missed_queries < options.temporal_score.max_missed_queries &&
      !state->previous_etas.empty()) {
    ++state->missed_queries;
  } else {
    state->previous_etas.clear();
    state->missed_queries = 0;
    state->previous_odometer = std::numeric_limits<double>::quiet_NaN();
  }
  state->consistency.miss(options.temporal_verification);
}

bool scoreCandidates(const QueryContext& ctx, const DatabaseQuery& q,
                     const DatabaseEntry& query_entry, bool with_groups, bool with_distribution,
                     LoopResult* r, std::vector<std::pair<EntryId, double>>* etas) {
  const Database& database = ctx.database;
  const LoopDetectorOptions& options = ctx.options;
  DetectorState& state = ctx.state;
  const auto finish = [&](LoopStatus status) {
    r->status = status;
    recordUnscoredQuery(options, &state);
    return false;
  };
  if (database.size() == 0) return finish(LoopStatus::kDatabaseTooSmall);

  const SimilarityOptions& so = options.similarity;
  // Normalisers (eqs. 2, 4): the same scores against I_{t-1}, the last entry
  // (or the one driven normaliser_distance_m back). They join the history
  // from the first keyframe on, so that the floor has its median ready when
  // the database is large enough to be queried.
  // The history keeps the score against that entry, not the lookback's
  // choice: the lookback's yardstick must not drift with its own choices.
  const EntryScores adjacent =
      database.score(q, normaliserEntry(database, so, query_entry.odometer));
  const Normalisers expected = state.normalisers.median();
  state.normalisers.push({adjacent.s_w, adjacent.s_g, adjacent.s_d},
                         static_cast<std::size_t>(so.normaliser_window));
  const EntryScores norm =
      lookBackNormaliser(database, q, so, query_entry.odometer, adjacent, expected.word);
  const Normalisers previous{norm.s_w, norm.s_g, norm.s_d};
  r->word_normaliser = norm.s_w;
  r->group_normaliser = with_groups ? norm.s_g : 0.0;
  r->distribution_normaliser = with_distribution ? norm.s_d : 0.0;
  const EntryId limit = candidateLimit(database, ctx.islands, query_entry.odometer);
  if (limit == 0) return finish(LoopStatus::kDatabaseTooSmall);
  // What eqs. 2 and 4 divide by: s(I_t, I_t-1), raised to the normaliser
  // floor where it is unusually small.
  const Normalisers divisor = flooredNormalisers(previous, expected, so.normaliser_floor);
  // A normaliser of 0 (I_{t-1} shares no word / group / occupied fan bin with
  // I_t) cannot divide eqs. 2 and 4 even when the minimum is set to 0 (a valid
  // value): such a keyframe is always low_normaliser, never inf/NaN scores.
  // Without the floor (the paper) the test reads s(I_t, I_t-1) itself. With
  // it, the floored divisor: a previous keyframe that shares little with this
  // one (keyframes 10-20 cm apart, a jolt, a roll) does not silence the
  // query while the recent keyframes scored normally; an image too poor to
  // score still gets scores too small for any island.
  const Normalisers& tested = so.normaliser_floor > 0.0 ? divisor : previous;
  if (lowNormaliser(tested, so, with_groups, with_distribution)) {
    return finish(LoopStatus::kLowNormaliser);
  }
  r->word_divisor = divisor.word;
  r->group_divisor = with_groups ? divisor.group : 0.0;
  r->distribution_divisor = with_distribution ? divisor.distribution : 0.0;

  const std::vector<EntryScores> scores = database.query(q, limit, with_groups, &ctx.scratch);
  r->candidates_scored = scores.size();
  finalScores(ctx, scores, divisor, with_groups, with_distribution, query_entry.odometer, etas);
  state.previous_etas = *etas;  // sorted by entry id, as the scores are
  state.missed_queries = 0;
  state.previous_odometer = query_entry.odometer;
  return true;
}

}  // namespace query_steps
}  // namespace bowg
