#include "detection/match_verification.h"

#include <algorithm>
#include <cmath>

#include "bowg/detection/metric_translation.h"

namespace bowg {
namespace query_steps {
namespace {

// The loop's translation in metres from the odometer between the match and
// a neighbour of it (metric_translation.h); the PnP pose replaces the
// essential matrix's so that rotation and translation belong together. An
// estimate longer than the odometry allows between the two keyframes (by
// the gates' own assumptions: odometryDistanceBound, `anchors` as the
// loop-anchored gate read them) is not published.
void estimateScale(const QueryContext& ctx, const Verifier& verifier,
                   const std::vector<AnchorEntries>& anchors, LoopResult* r) {
  const MetricTranslationOptions& mo = ctx.options.metric;
  if (!r->has_relative_pose) return;
  if (!mo.enabled) {
    r->metric_status = MetricTranslationStatus::kDisabled;
    return;
  }
  const auto& entries = ctx.database.entries();
  if (!std::isfinite(entries[r->match_id].odometer)) {
    r->metric_status = MetricTranslationStatus::kNoOdometry;
    return;
  }
  const std::vector<EntryId> ids = chooseScaleNeighbours(entries, r->match_id, mo);
  if (ids.empty()) {
    r->metric_status = MetricTranslationStatus::kNoNeighbour;
    return;
  }
  const DatabaseEntry& m = entries[r->match_id];
  EntryViewStorage match_storage;
  std::vector<EntryViewStorage> storage(ids.size());
  std::vector<ScaleNeighbour> neighbours(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    neighbours[i].view = verifier.entry(ids[i], &storage[i]);
    neighbours[i].baseline_m = std::fabs(entries[ids[i]].odometer - m.odometer);
  }
  const MetricTranslation t = estimateMetricTranslation(
      r->inlier_correspondences, verifier.intrinsics(), verifier.entry(r->match_id, &match_storage),
      neighbours, m.intrinsics, ctx.options.geometric, mo);
  r->metric_status = t.status;
  if (t.status != MetricTranslationStatus::kEstimated) return;
  const double norm =
      std::sqrt(t.translation[0] * t.translation[0] + t.translation[1] * t.translation[1] +
                t.translation[2] * t.translation[2]);
  if (!(norm <= odometryDistanceBound(verifier.queryEntry(), m, anchors, ctx.options.islands))) {
    r->metric_status = MetricTranslationStatus::kOutsideOdometry;
    return;
  }
  r->translation_scale_known = true;
  std::copy(t.translation, t.translation + 3, r->translation_m);
  std::copy(t.covariance, t.covariance + 9, r->translation_covariance);
  std::copy(t.rotation, t.rotation + 9, r->rotation);
  if (norm > 0) {
    for (int i = 0; i < 3; ++i) r->translation_direction[i] = t.translation[i] / norm;
  }
}

}  // namespace

// Geometric verification of the best entry of the chosen island (done
// already when re-ranking); the loop, its relative pose and its scale.
void verifyMatch(const QueryContext& ctx, const Island& island, IslandChoice* choice,
                 Verifier* verifier, const std::vector<AnchorEntries>& anchors,
                 Clock::time_point t_verify, LoopResult* r) {
  const GeometricVerificationOptions& go = ctx.options.geometric;
  const DatabaseEntry& match = ctx.database.entry(island.best_entry);
  r->match_id = match.id;
  r->match_stamp = match.stamp;
  r->match_mission = match.mission;
  r->match_mission_name = ctx.database.missions().find(match.mission)->name;
  if (!go.enabled) {
    r->status = LoopStatus::kLoopDetected;
    return;
  }
  GeometricVerificationResult& g = choice->g;
  if (!choice->pairs.empty()) {
    g = verifyCorrespondences(choice->pairs, verifier->query(),
                              verifier->features(island.best_entry), verifier->intrinsics(), go);
  } else if (!choice->verified) {
    g = verifyGeometry(verifier->query(), verifier->match(island.best_entry),
                       verifier->intrinsics(), go);
  }
  r->timings.verification_ms = choice->rerank_ms + msBetween(t_verify, Clock::now());
  r->status = g.status;
  r->correspondences = g.correspondences;
  r->inliers = g.inliers;
  if (g.status != LoopStatus::kLoopDetected) {
    r->match_id = 0;
    r->match_stamp = 0;
    r->match_mission = 0;
    r->match_mission_name.clear();
    return;
  }
  if (!g.has_relative_pose && verifier->intrinsics().valid) {
    g.has_relative_pose = relativePoseFromCorrespondences(
        g.inlier_correspondences, verifier->intrinsics(), go.ransac_threshold_px,
        go.ransac_confidence, g.rotation, g.translation_direction);
  }
  r->inlier_correspondences = std::move(g.inlier_correspondences);
  r->has_relative_pose = g.has_relative_pose;
  std::copy(g.rotation, g.rotation + 9, r->rotation);
  std::copy(g.translation_direction, g.translation_direction + 3, r->translation_direction);
  estimateScale(ctx, *verifier, anchors, r);
  r->timings.verification_ms = choice->rerank_ms + msBetween(t_verify, Clock::now());
}
}  // namespace query_steps
}  // namespace bowg
