// The first stage of a query: the normalisers and every candidate's final
// score (eqs. 2-5 and 9, then eqs. 6-7 with the previous query's scores),
// among the entries the recent-exclusion window leaves. Internal to the
// detection stage (query_steps.h).
#pragma once

#include <utility>
#include <vector>

#include "detection/query_context.h"

namespace bowg {
namespace query_steps {

// A query that cannot be scored (no features, database too small, normaliser
// too small, no candidate): eq. 7's previous scores survive up to
// temporal_score.max_missed_queries such queries and the temporal chain up to
// temporal_verification.max_missed_queries (0 = the paper: forgotten at once).
void recordUnscoredQuery(const LoopDetectorOptions& options, DetectorState* state);

/// The query's final scores of every candidate, into ctx.candidates and
/// `etas` (entry, eta), sorted by entry id. False when the query stops
/// before its candidates are scored (database too small, low normaliser);
/// `r` then has its status. Updates the temporal memory.
bool scoreCandidates(const QueryContext& ctx, const DatabaseQuery& q,
                     const DatabaseEntry& query_entry, bool with_groups, bool with_distribution,
                     LoopResult* r, std::vector<std::pair<EntryId, double>>* etas);

}  // namespace query_steps
}  // namespace bowg
