// The odometry gates of a query (candidate_gates.h).
#include "detection/candidate_gates.h"

#include <algorithm>

#include "bowg/detection/islands.h"

namespace bowg {
namespace query_steps {

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

void applyOdometryGates(const QueryContext& ctx, const DatabaseEntry& query_entry,
                        const std::vector<AnchorEntries>& anchors,
                        std::vector<std::pair<EntryId, double>>* etas, LoopResult* r) {
  // Candidates under the query's threshold are left to islandsOf and not
  // counted as gated.
  const IslandOptions& io = ctx.islands;
  const bool anchored = !anchors.empty();
  if (!(io.odometry_gate_m > 0.0) && !(io.heading_gate_deg > 0.0) && !anchored) return;
  const auto outside = [&](const std::pair<EntryId, double>& c) {
    if (c.second < io.min_score) return false;
    const DatabaseEntry& e = ctx.database.entry(c.first);
    if (anchored && !withinCrossRunAnchors(query_entry, e, anchors, io)) {
      ++r->candidates_gated_cross_run;
      return true;
    }
    if (!withinOdometryGate(query_entry, e, io)) return true;
    if (!withinHeadingGate(query_entry, e, io)) {
      ++r->candidates_gated_heading;
      return true;
    }
    return anchored && !withinLoopAnchors(query_entry, e, anchors, io);
  };
  const auto end = std::remove_if(etas->begin(), etas->end(), outside);
  r->candidates_gated = static_cast<std::size_t>(etas->end() - end);
  etas->erase(end, etas->end());
}

}  // namespace query_steps
}  // namespace bowg
