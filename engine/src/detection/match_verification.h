// The last step of a query: the geometric verification of the chosen
// island's best entry (already done when the re-ranking verified it), the
// loop's relative pose and its metric translation. Internal to the detection
// stage.
#pragma once

#include <vector>

#include "bowg/detection/islands.h"
#include "bowg/detection/odometry_gate.h"
#include "detection/island_choice.h"
#include "detection/query_context.h"
#include "detection/verifier.h"

namespace bowg {
namespace query_steps {

// Geometric verification of the best entry of the chosen island (done
// already when re-ranking); the loop, its relative pose and its scale.
void verifyMatch(const QueryContext& ctx, const Island& island, IslandChoice* choice,
                 Verifier* verifier, const std::vector<AnchorEntries>& anchors,
                 Clock::time_point t_verify, LoopResult* r);

}  // namespace query_steps
}  // namespace bowg
