// Temporal verification of the chosen island (temporal_check.h).
#include "detection/temporal_check.h"

namespace bowg {
namespace query_steps {
namespace {

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

}  // namespace

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

}  // namespace query_steps
}  // namespace bowg
