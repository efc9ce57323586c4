// One query's part in the verified chain (verified_chain.h): its verified
// matches and their unique inliers (repeated_texture.h). Internal to the
// detection stage.
#pragma once

#include <vector>

#include "bowg/detection/islands.h"
#include "bowg/detection/verified_chain.h"
#include "detection/island_choice.h"
#include "detection/query_context.h"
#include "detection/verifier.h"

namespace bowg {
namespace query_steps {

/// The query's verified matches: the chosen island's best entry and the
/// re-ranking's runner-up, those with at least min_inliers inliers. With
/// min_unique_inliers > 0 each gets its unique inliers: the inliers on query
/// features that none of the recent past's keyframes (repeatedTextureEntries)
/// corresponds to.
ChainQuery chainQuery(const QueryContext& ctx, EntryId query_id, const DatabaseEntry& query_entry,
                      const std::vector<Island>& islands, const IslandChoice& choice,
                      Verifier* verifier);

/// What chainStep compares in this query's context.
inline ChainContext chainContext(const QueryContext& ctx) {
  return ChainContext{ctx.database.odometers(), ctx.state.place_links,
                      ctx.options.temporal_verification, ctx.options.islands.odometry_gate_drift};
}

}  // namespace query_steps
}  // namespace bowg
