// One query of the loop detector (query_steps.h), in steps: scores, the
// odometry gates, islands with geometric re-ranking (island_choice.h),
// temporal verification or the verified chain (chain_query.h), geometric
// verification (match_verification.h).
#include "detection/query_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "bowg/detection/geometric_verification.h"
#include "bowg/detection/islands.h"
#include "bowg/detection/odometry_gate.h"
#include "bowg/detection/odometry_input.h"
#include "bowg/scoring/similarity.h"
#include "bowg/scoring/temporal_alignment.h"
#include "detection/chain_query.h"
#include "detection/island_choice.h"
#include "detection/match_verification.h"
#include "detection/verifier.h"

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

// The recent-exclusion window of the query: recent_exclusion_odometer_m
// replaces recent_exclusion_m when the query has an odometer but no
// odometry position.
IslandOptions exclusionWindow(const IslandOptions& options, const DatabaseEntry& query) {
  IslandOptions window = options;
  if (odometryInput(query.odometer, query.position) == OdometryInput::kOdometer &&
      options.recent_exclusion_odometer_m > 0.0) {
    window.recent_exclusion_m = options.recent_exclusion_odometer_m;
  }
  return window;
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

// The query's final scores of every candidate (and the step's outcome): false
// when the query stops before its candidates are scored (database too small,
// low normaliser); `r` then has its status. Updates the temporal memory.
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
  const EntryScores norm = database.score(q, normaliserEntry(database, so, query_entry.odometer));
  const Normalisers previous{norm.s_w, norm.s_g, norm.s_d};
  const Normalisers expected = state.normalisers.median();
  state.normalisers.push(previous, static_cast<std::size_t>(so.normaliser_window));
  r->word_normaliser = norm.s_w;
  r->group_normaliser = with_groups ? norm.s_g : 0.0;
  r->distribution_normaliser = with_distribution ? norm.s_d : 0.0;
  const EntryId limit =
      candidateLimit(database, exclusionWindow(options.islands, query_entry), query_entry.odometer);
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

  const std::vector<EntryScores> scores = database.query(q, limit, with_groups);
  r->candidates_scored = scores.size();
  etas->reserve(scores.size());
  // Eq. 7's predecessor in metres when odometry allows it
  // (TemporalScoreOptions::alignment_window_m), else in keyframes.
  const TemporalScoreOptions& to = options.temporal_score;
  const bool metric_alignment = to.alignment_window_m > 0.0 && !std::isnan(query_entry.odometer) &&
                                !std::isnan(state.previous_odometer);
  const double driven = metric_alignment ? query_entry.odometer - state.previous_odometer : 0.0;
  ctx.candidates.reserve(scores.size());
  // The scores come in ascending entry order: one forward walk of the
  // temporal memory for all of them.
  AlignedPreviousScores aligned =
      metric_alignment ? AlignedPreviousScores(state.previous_etas, database.odometers(), driven,
                                               to.alignment_window_m)
                       : AlignedPreviousScores(state.previous_etas, state.missed_queries, to);
  for (const EntryScores& s : scores) {
    CandidateScores c;
    c.entry = s.entry;
    c.eta_w = normaliseScore(s.s_w, divisor.word);
    c.eta_g = with_groups ? normaliseScore(s.s_g, divisor.group) : 0.0;
    c.eta_d = with_distribution ? normaliseScore(s.s_d, divisor.distribution) : 0.0;
    c.eta_sim =
        combineSimilarity(c.eta_w, c.eta_g, c.eta_d, options.word_groups, options.distribution, so);
    // Eqs. 6-7: eta(t-1, tj-1) is the previous query's final score of the
    // entry before this one (alignment_window 0), or the best-aligned one
    // near it (temporal_alignment.h); 0 when none was scored then.
    c.eta = temporalScore(c.eta_sim, aligned(s.entry), options.temporal_score);
    ctx.candidates.push_back(c);
    etas->emplace_back(c.entry, c.eta);
  }
  state.previous_etas = *etas;  // sorted by entry id, as the scores are
  state.missed_queries = 0;
  state.previous_odometer = query_entry.odometer;
  return true;
}

// TemporalVerificationOptions::linked_places: whether the chosen island
// (followed[0]) is one place, by accepted loops, with another followed
// island whose chain passes (the chains as they stand before this query's
// update). Then the robot is where that chain says, seen on another lap.
bool continuesLinkedChain(const QueryContext& ctx, const std::vector<Island>& followed,
                          double query_m) {
  const TemporalVerificationOptions& tv = ctx.options.temporal_verification;
  for (std::size_t i = 1; i < followed.size(); ++i) {
    if (ctx.state.consistency.chainTo(followed[i], tv, query_m) > tv.k &&
        ctx.state.place_links.linked(followed[0], followed[i])) {
      return true;
    }
  }
  return false;
}

// The recent loops of this odometry run as the loop-anchored gate reads them
// (none when it is off).
std::vector<AnchorEntries> loopAnchors(const QueryContext& ctx) {
  std::vector<AnchorEntries> anchors;
  if (!(ctx.options.islands.odometry_anchor_m > 0.0)) return anchors;
  for (const LoopAnchor& a : ctx.state.recent_loops) {
    if (a.query < ctx.database.size() && a.match < ctx.database.size()) {
      anchors.push_back(AnchorEntries{&ctx.database.entry(a.query), &ctx.database.entry(a.match)});
    }
  }
  return anchors;
}

// The odometry gates: candidates above the threshold where the odometry says
// the robot cannot be are not candidates (the temporal memory keeps their
// scores: the gates judge places, not the score's history). Returns how many
// it removed.
std::size_t applyOdometryGates(const QueryContext& ctx, const DatabaseEntry& query_entry,
                               const std::vector<AnchorEntries>& anchors,
                               std::vector<std::pair<EntryId, double>>* etas) {
  const IslandOptions& io = ctx.options.islands;
  const bool anchored = !anchors.empty();
  if (!(io.odometry_gate_m > 0.0) && !anchored) return 0;
  const auto outside = [&](const std::pair<EntryId, double>& c) {
    if (c.second < io.min_score) return false;
    const DatabaseEntry& e = ctx.database.entry(c.first);
    return !withinOdometryGate(query_entry, e, io) ||
           (anchored && !withinLoopAnchors(query_entry, e, anchors, io));
  };
  const auto end = std::remove_if(etas->begin(), etas->end(), outside);
  const std::size_t gated = static_cast<std::size_t>(etas->end() - end);
  etas->erase(end, etas->end());
  return gated;
}

// The temporal verification of the chosen island (Sec. III-D): its chain of
// consistent islands over the previous queries (TemporalVerificationOptions:
// several hypotheses, places joined by loops, a recent loop's anchor).
// Updates the chains whatever the verdict.
bool temporallyConsistent(const QueryContext& ctx, const std::vector<Island>& islands,
                          const IslandChoice& choice, const DatabaseEntry& query_entry,
                          const std::vector<AnchorEntries>& anchors) {
  const Island& island = islands[choice.chosen];
  // The followed hypotheses (TemporalVerificationOptions::hypotheses): the
  // chosen island first, then the best-scored others.
  std::vector<Island> followed{island};
  const TemporalVerificationOptions& tv = ctx.options.temporal_verification;
  const std::size_t wanted = static_cast<std::size_t>(tv.hypotheses);
  for (std::size_t i = 0; i < islands.size() && followed.size() < wanted; ++i) {
    if (i != choice.chosen) followed.push_back(islands[i]);
  }
  const bool linked = tv.linked_places && continuesLinkedChain(ctx, followed, query_entry.odometer);
  const bool anchored_chain =
      tv.anchored_chain && !anchors.empty() &&
      anchoredByRecentLoop(query_entry, ctx.database.entry(island.best_entry), anchors,
                           ctx.options.islands);
  return ctx.state.consistency.update(followed, 0, tv, query_entry.odometer) || linked ||
         anchored_chain;
}

// A query's record in the verified chain, pushed however the query ends.
struct ChainRecord {
  VerifiedChain& chain;
  ChainQuery query;
  ~ChainRecord() { chain.push(query); }
};

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

void runQuery(const QueryContext& ctx, const DatabaseQuery& q, const DatabaseEntry& query_entry,
              const CameraIntrinsics& intrinsics, bool with_groups, bool with_distribution,
              LoopResult* r) {
  const LoopDetectorOptions& options = ctx.options;
  const bool chain_on = options.chain.length > 0;
  ChainRecord record{ctx.state.verified_chain, ChainQuery()};
  record.query.query = r->query_id;
  record.query.odometer = query_entry.odometer;
  const auto t_query = Clock::now();
  std::vector<std::pair<EntryId, double>> etas;
  const bool scored =
      scoreCandidates(ctx, q, query_entry, with_groups, with_distribution, r, &etas);
  const auto t_islands = Clock::now();
  r->timings.query_ms = msBetween(t_query, t_islands);
  if (!scored) return;
  if (etas.empty()) {
    r->status = LoopStatus::kNoCandidates;
    recordUnscoredQuery(options, &ctx.state);
    return;
  }
  r->has_candidate = true;
  r->best = *std::max_element(
      ctx.candidates.begin(), ctx.candidates.end(),
      [](const CandidateScores& a, const CandidateScores& b) { return a.eta < b.eta; });
  const std::vector<AnchorEntries> anchors = loopAnchors(ctx);
  r->candidates_gated = applyOdometryGates(ctx, query_entry, anchors, &etas);
  // Islands (Sec. III-D, eq. 10) and their geometric re-ranking.
  std::vector<Island> islands = computeIslands(std::move(etas), options.islands);
  for (Island& i : islands) {
    i.first_m = ctx.database.entry(i.first).odometer;
    i.last_m = ctx.database.entry(i.last).odometer;
  }
  if (islands.empty()) {
    r->status = LoopStatus::kNoScoreAboveThreshold;
    ctx.state.consistency.miss(options.temporal_verification);
    r->timings.islands_ms = msBetween(t_islands, Clock::now());
    return;
  }
  Verifier verifier(ctx.vocabulary, ctx.database, query_entry, intrinsics,
                    options.geometric.exhaustive);
  IslandChoice choice = chooseIsland(islands, options.geometric, &verifier);
  const Island& island = islands[choice.chosen];
  r->island_first = island.first;
  r->island_last = island.last;
  r->island_score = island.score;
  const auto it =
      std::lower_bound(ctx.candidates.begin(), ctx.candidates.end(), island.best_entry,
                       [](const CandidateScores& c, EntryId id) { return c.entry < id; });
  if (it != ctx.candidates.end() && it->entry == island.best_entry) r->best = *it;
  bool consistent = temporallyConsistent(ctx, islands, choice, query_entry, anchors);
  // A loop that the odometry positions place (a recent loop's anchor) keeps
  // the temporal verification; any other needs the verified chain instead.
  const bool placed = !anchors.empty() && query_entry.position.known() &&
                      anchoredByRecentLoop(query_entry, ctx.database.entry(island.best_entry),
                                           anchors, options.islands);
  if (chain_on) {
    verifyChoice(islands, options.geometric, &verifier, &choice);
    record.query = chainQuery(ctx, r->query_id, query_entry, islands, choice, &verifier);
  }
  const auto t_verify = Clock::now();
  r->timings.islands_ms = msBetween(t_islands, t_verify) - choice.rerank_ms;
  r->timings.verification_ms = choice.rerank_ms;
  if (chain_on && !placed && record.query.matches > 0 &&
      record.query.match[0].entry == island.best_entry) {
    if (!ctx.state.verified_chain.passes(record.query, options.chain, chainContext(ctx))) {
      r->status = LoopStatus::kNoVerifiedChain;
      return;
    }
    consistent = true;
  } else if (chain_on && !placed && choice.verified) {
    consistent = true;  // too few inliers: verifyMatch says so
  }
  if (!consistent) {
    r->status = LoopStatus::kNoTemporalConsistency;
    return;
  }
  verifyMatch(ctx, island, &choice, &verifier, anchors, t_verify, r);
  if (r->status == LoopStatus::kLoopDetected) {
    record.query.published = true;
    ctx.state.place_links.link(r->query_id, r->match_id);
    std::vector<LoopAnchor>& recent = ctx.state.recent_loops;
    if (recent.size() == kLoopAnchors) recent.erase(recent.begin());
    recent.push_back(LoopAnchor{r->query_id, r->match_id});
  }
}

}  // namespace query_steps
}  // namespace bowg
