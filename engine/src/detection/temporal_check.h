// The temporal verification of a query's chosen island (Sec. III-D): its
// chain of consistent islands over the previous queries, with the
// TemporalVerificationOptions extensions (several hypotheses, places joined
// by loops, a recent loop's anchor). Internal to the detection stage
// (query_steps.h).
#pragma once

#include <vector>

#include "bowg/detection/islands.h"
#include "bowg/detection/odometry_gate.h"
#include "detection/island_choice.h"
#include "detection/query_context.h"

namespace bowg {
namespace query_steps {

/// Whether the chosen island passes; updates the chains whatever the verdict.
bool temporallyConsistent(const QueryContext& ctx, const std::vector<Island>& islands,
                          const IslandChoice& choice, const DatabaseEntry& query_entry,
                          const std::vector<AnchorEntries>& anchors);

}  // namespace query_steps
}  // namespace bowg
