// One query of the loop detector (query_steps.h) as its stages: scores
// (candidate_scoring.h), the odometry gates (candidate_gates.h), islands
// with geometric re-ranking (island_choice.h), temporal verification
// (temporal_check.h) or the verified chain (chain_query.h), geometric
// verification (match_verification.h).
#include "detection/query_steps.h"

#include <algorithm>
#include <utility>

#include "bowg/detection/islands.h"
#include "bowg/detection/odometry_gate.h"
#include "detection/candidate_gates.h"
#include "detection/candidate_scoring.h"
#include "detection/chain_query.h"
#include "detection/island_choice.h"
#include "detection/match_verification.h"
#include "detection/temporal_check.h"

namespace bowg {
namespace query_steps {
namespace {

// A query's record in the verified chain, pushed however the query ends.
struct ChainRecord {
  VerifiedChain& chain;
  ChainQuery query;
  ~ChainRecord() { chain.push(query); }
};

// Islands (Sec. III-D, eq. 10) of the gated candidates above the query's
// threshold (QueryContext::islands: higher with images only), with the odometers
// of their ends.
std::vector<Island> islandsOf(const QueryContext& ctx,
                              std::vector<std::pair<EntryId, double>>&& etas) {
  std::vector<Island> islands = computeIslands(std::move(etas), ctx.islands);
  for (Island& i : islands) {
    i.first_m = ctx.database.entry(i.first).odometer;
    i.last_m = ctx.database.entry(i.last).odometer;
  }
  return islands;
}

// The candidate the keyframe's status is about, and its mission.
void setBest(const QueryContext& ctx, const CandidateScores& best, LoopResult* r) {
  r->best = best;
  r->best_mission = ctx.database.entry(best.entry).mission;
  r->best_mission_name = ctx.database.missions().find(r->best_mission)->name;
}

// The chosen island in the result, and its best entry's scores as r->best.
void recordIsland(const QueryContext& ctx, const Island& island, LoopResult* r) {
  r->island_first = island.first;
  r->island_last = island.last;
  r->island_score = island.score;
  const auto it =
      std::lower_bound(ctx.candidates.begin(), ctx.candidates.end(), island.best_entry,
                       [](const CandidateScores& c, EntryId id) { return c.entry < id; });
  if (it != ctx.candidates.end() && it->entry == island.best_entry) setBest(ctx, *it, r);
}

// What the verified chain says of a query that the odometry positions do
// not place: it judges a match it verified itself; a choice the re-ranking
// verified with too few inliers passes here (verifyMatch refuses it).
enum class ChainVerdict { kNotAsked, kPasses, kFails };
ChainVerdict chainVerdict(const QueryContext& ctx, const DatabaseEntry& query_entry,
                          const ChainQuery& query, const Island& island,
                          const IslandChoice& choice) {
  if (query.matches > 0 && query.match[0].entry == island.best_entry) {
    ChainContext context = chainContext(ctx);
    context.position_gated =
        odometryGateApplies(query_entry, ctx.database.entry(query.match[0].entry), ctx.islands);
    return ctx.state.verified_chain.passes(query, ctx.options.chain, context)
               ? ChainVerdict::kPasses
               : ChainVerdict::kFails;
  }
  return choice.verified ? ChainVerdict::kPasses : ChainVerdict::kNotAsked;
}

// A published loop joins its places and becomes a recent loop's anchor.
void rememberLoop(const QueryContext& ctx, const LoopResult& r) {
  ctx.state.place_links.link(r.query_id, r.match_id);
  std::vector<LoopAnchor>& recent = ctx.state.recent_loops;
  if (recent.size() == kLoopAnchors) recent.erase(recent.begin());
  recent.push_back(LoopAnchor{r.query_id, r.match_id});
}

}  // namespace

void runQuery(const QueryContext& ctx, const DatabaseQuery& q, const DatabaseEntry& query_entry,
              const CameraIntrinsics& intrinsics, bool with_groups, bool with_distribution,
              LoopResult* r) {
  const LoopDetectorOptions& options = ctx.options;
  const bool chain_on = options.chain.length > 0;
  ChainRecord record{ctx.state.verified_chain, ChainQuery()};
  record.query.query = r->query_id;
  record.query.odometer = query_entry.odometer;
  // 1. Every candidate's score.
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
  setBest(ctx,
          *std::max_element(
              ctx.candidates.begin(), ctx.candidates.end(),
              [](const CandidateScores& a, const CandidateScores& b) { return a.eta < b.eta; }),
          r);
  // 2. The odometry gates.
  const std::vector<AnchorEntries> anchors = loopAnchors(ctx);
  applyOdometryGates(ctx, query_entry, anchors, &etas, r);
  // 3. Islands, and the choice among them by geometric re-ranking.
  std::vector<Island> islands = islandsOf(ctx, std::move(etas));
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
  recordIsland(ctx, island, r);
  // 4. Temporal verification. A loop that the odometry positions place (a
  //    recent loop's anchor) keeps it; any other needs the verified chain.
  bool consistent = temporallyConsistent(ctx, islands, choice, query_entry, anchors);
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
  const ChainVerdict verdict = chain_on && !placed
                                   ? chainVerdict(ctx, query_entry, record.query, island, choice)
                                   : ChainVerdict::kNotAsked;
  if (verdict == ChainVerdict::kFails) {
    r->status = LoopStatus::kNoVerifiedChain;
    return;
  }
  if (!consistent && verdict != ChainVerdict::kPasses) {
    r->status = LoopStatus::kNoTemporalConsistency;
    return;
  }
  // 5. Geometric verification of the match.
  verifyMatch(ctx, island, &choice, &verifier, anchors, t_verify, r);
  if (r->status == LoopStatus::kLoopDetected) {
    record.query.published = true;
    rememberLoop(ctx, *r);
  }
}

}  // namespace query_steps
}  // namespace bowg
