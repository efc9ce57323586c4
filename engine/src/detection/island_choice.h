// The geometric re-ranking of a query's islands (GeometricVerificationOptions::
// candidates): which island is the query's, by the inliers of the islands'
// best entries. Internal to the detection stage.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "bowg/detection/geometric_verification.h"
#include "bowg/detection/islands.h"
#include "detection/verifier.h"

namespace bowg {
namespace query_steps {

struct IslandChoice {
  std::size_t chosen = 0;         ///< index into the islands
  GeometricVerificationResult g;  ///< of its best entry, when verified
  bool verified = false;
  /// Its best entry's correspondences when the re-ranking chose it by them
  /// without RANSAC (GeometricVerificationOptions::rerank_ransacs 0); empty
  /// otherwise (a choice by correspondences has at least min_inliers >= 8).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  double rerank_ms = 0;
  /// The re-ranking's runner-up, when a second RANSAC ran: its island and
  /// verification (its inliers a lower bound when the RANSAC was bounded by
  /// the winner's count). The verified chain follows both.
  bool has_runner_up = false;
  std::size_t runner_up = 0;
  GeometricVerificationResult runner_up_g;
};

// Geometric re-ranking (GeometricVerificationOptions::candidates): the
// query's island is the one of the top `candidates` whose best entry has the
// most inliers (ties: the better-scored island), among those with at least
// min_inliers correspondences: only they can be loops. When none has that
// many, or with 1 candidate, it is the best-scored island, verified after the
// temporal verification (the paper). The correspondences are cheap; RANSAC
// is the cost, and in an aliased pipe most queries have no candidate that
// could pass: RANSAC runs on at most `rerank_ransacs` candidates, those with
// the most correspondences (0: the one with the most correspondences is
// chosen, and verified only if it passes the temporal verification).
IslandChoice chooseIsland(const std::vector<Island>& islands,
                          const GeometricVerificationOptions& go, Verifier* verifier);

/// Verifies the chosen island's best entry now when the re-ranking did not
/// (one island, or a choice by correspondences): the verified chain needs
/// every query's verified match, not only those that pass the temporal
/// verification. verifyMatch then reuses it. No-op when already verified or
/// with geometric verification off.
void verifyChoice(const std::vector<Island>& islands, const GeometricVerificationOptions& go,
                  Verifier* verifier, IslandChoice* choice);

}  // namespace query_steps
}  // namespace bowg
