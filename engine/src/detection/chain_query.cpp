#include "detection/chain_query.h"

#include "bowg/detection/repeated_texture.h"

namespace bowg {
namespace query_steps {

ChainQuery chainQuery(const QueryContext& ctx, EntryId query_id, const DatabaseEntry& query_entry,
                      const std::vector<Island>& islands, const IslandChoice& choice,
                      Verifier* verifier) {
  ChainQuery q;
  q.query = query_id;
  q.odometer = query_entry.odometer;
  const int min_inliers = ctx.options.geometric.min_inliers;
  const GeometricVerificationResult* verified[2] = {nullptr, nullptr};
  EntryId entries[2] = {0, 0};
  int n = 0;
  if (choice.verified && choice.g.inliers >= min_inliers) {
    verified[n] = &choice.g;
    entries[n++] = islands[choice.chosen].best_entry;
  }
  if (choice.has_runner_up && choice.runner_up_g.inliers >= min_inliers) {
    verified[n] = &choice.runner_up_g;
    entries[n++] = islands[choice.runner_up].best_entry;
  }
  if (n == 0) return q;
  const VerifiedChainOptions& co = ctx.options.chain;
  std::vector<char> repeated;
  if (co.min_unique_inliers > 0) {
    repeated.assign(query_entry.descriptorCount(), 0);
    const VerificationView qv = verifier->query();
    for (const EntryId id :
         repeatedTextureEntries(ctx.database, query_entry.odometer, co, ctx.options.islands)) {
      markRepeated(qv, verifier->cached(id, &ctx.views), ctx.options.geometric, &repeated);
    }
  }
  for (int i = 0; i < n; ++i) {
    ChainMatch m;
    m.entry = entries[i];
    if (!repeated.empty())
      m.unique_inliers = uniqueInliers(verified[i]->inlier_correspondences, repeated);
    q.add(m);
  }
  return q;
}

}  // namespace query_steps
}  // namespace bowg
