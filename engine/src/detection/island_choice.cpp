#include "detection/island_choice.h"

#include <algorithm>
#include <chrono>

namespace bowg {
namespace query_steps {
namespace {

double msSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

IslandChoice chooseIsland(const std::vector<Island>& islands,
                          const GeometricVerificationOptions& go, Verifier* verifier) {
  IslandChoice c;
  const std::size_t reranked =
      go.enabled ? std::min(islands.size(), static_cast<std::size_t>(go.candidates)) : 1;
  if (reranked <= 1) return c;
  const auto t_rerank = std::chrono::steady_clock::now();
  const VerificationView qv = verifier->query();
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> pairs(reranked);
  std::vector<std::size_t> order(reranked);
  for (std::size_t i = 0; i < reranked; ++i) {
    pairs[i] = findCorrespondences(qv, verifier->match(islands[i].best_entry), go);
    order[i] = i;
  }
  // RANSAC (the cost) in decreasing number of correspondences. Inliers are a
  // subset of the correspondences, so once a candidate has fewer
  // correspondences than min_inliers (it cannot be a loop) or than the best
  // inlier count so far (or as many, and a worse score: ties go to the
  // better-scored island), neither it nor any later one can win: the choice
  // is the one of trying every candidate that could be a loop.
  std::stable_sort(order.begin(), order.end(), [&pairs](std::size_t a, std::size_t b) {
    return pairs[a].size() > pairs[b].size();
  });
  if (go.rerank_ransacs == 0) {
    if (static_cast<int>(pairs[order[0]].size()) >= go.min_inliers) {
      c.chosen = order[0];
      c.pairs = std::move(pairs[order[0]]);
    }
    c.rerank_ms = msSince(t_rerank);
    return c;
  }
  bool have = false;
  int ransacs = 0;
  for (const std::size_t i : order) {
    const int n = static_cast<int>(pairs[i].size());
    if (n < go.min_inliers || (have && n < c.g.inliers)) break;
    if (have && n == c.g.inliers && i > c.chosen) continue;
    if (ransacs == go.rerank_ransacs) break;
    ++ransacs;
    // After a loop, only a model with more inliers (as many, for a
    // better-scored island) changes the choice: RANSAC's samples are
    // bounded for that count (GeometricVerificationOptions::
    // ransac_bound_confidence).
    const int decisive =
        have && c.g.inliers >= go.min_inliers ? c.g.inliers + (i < c.chosen ? 0 : 1) : 0;
    // No intrinsics: the relative pose (an essential matrix) is only worth
    // its cost for the loop, once it is accepted (verifyMatch).
    GeometricVerificationResult gi = verifyCorrespondences(
        pairs[i], qv, verifier->features(islands[i].best_entry), CameraIntrinsics(), go, decisive);
    if (!have || gi.inliers > c.g.inliers || (gi.inliers == c.g.inliers && i < c.chosen)) {
      if (have) {
        c.has_runner_up = true;
        c.runner_up = c.chosen;
        c.runner_up_g = std::move(c.g);
      }
      c.g = std::move(gi);
      c.chosen = i;
      have = true;
    } else {
      c.has_runner_up = true;
      c.runner_up = i;
      c.runner_up_g = std::move(gi);
    }
  }
  c.verified = have;
  c.rerank_ms = msSince(t_rerank);
  return c;
}

void verifyChoice(const std::vector<Island>& islands, const GeometricVerificationOptions& go,
                  Verifier* verifier, IslandChoice* choice) {
  if (choice->verified || !go.enabled) return;
  const auto t = std::chrono::steady_clock::now();
  const EntryId entry = islands[choice->chosen].best_entry;
  if (!choice->pairs.empty()) {
    choice->g = verifyCorrespondences(choice->pairs, verifier->query(), verifier->features(entry),
                                      CameraIntrinsics(), go);
    choice->pairs.clear();
  } else {
    choice->g = verifyGeometry(verifier->query(), verifier->match(entry), CameraIntrinsics(), go);
  }
  choice->verified = true;
  choice->rerank_ms += msSince(t);
}

}  // namespace query_steps
}  // namespace bowg
