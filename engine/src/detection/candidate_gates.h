// The second stage of a query: the odometry gates (odometry_gate.h) applied
// to the scored candidates. Candidates above the threshold where the
// odometry says the robot cannot be are not candidates; the temporal memory
// keeps their scores (the gates judge places, not the score's history).
// Internal to the detection stage (query_steps.h).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "bowg/detection/odometry_gate.h"
#include "detection/query_context.h"

namespace bowg {
namespace query_steps {

/// The recent loops of this odometry run as the loop-anchored gate reads
/// them (none when it is off).
std::vector<AnchorEntries> loopAnchors(const QueryContext& ctx);

/// Removes the gated candidates from `etas`; counts them in
/// r->candidates_gated (and r->candidates_gated_cross_run).
void applyOdometryGates(const QueryContext& ctx, const DatabaseEntry& query_entry,
                        const std::vector<AnchorEntries>& anchors,
                        std::vector<std::pair<EntryId, double>>* etas, LoopResult* r);

}  // namespace query_steps
}  // namespace bowg
