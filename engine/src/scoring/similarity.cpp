// Combination of the normalised scores (paper eqs. 5 and 9) and the adaptive
// temporal score (eqs. 6-7).
#include "bowg/scoring/similarity.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace bowg {
namespace {

void requireFinite(const char* function, const char* name, double v) {
  if (!std::isfinite(v)) {
    throw std::invalid_argument(std::string(function) + ": " + name + " must be finite (got " +
                                std::to_string(v) + ")");
  }
}

}  // namespace

double combineSimilarity(double eta_w, double eta_g, double eta_d, const WordGroupOptions& groups,
                         const DistributionOptions& distribution,
                         const SimilarityOptions& similarity) {
  // Only the scores a combination uses are checked: the caller may leave the
  // score of a switched-off module unset.
  requireFinite("combineSimilarity", "eta_w", eta_w);
  if (groups.enabled) requireFinite("combineSimilarity", "eta_g", eta_g);
  if (distribution.enabled) requireFinite("combineSimilarity", "eta_d", eta_d);
  return similarity_terms::combined(eta_w, eta_g, eta_d, groups.enabled, distribution.enabled,
                                    similarity.lambda_1, similarity.lambda_2);
}

double previousScoreWeight(double eta, double eta_prev, const TemporalScoreOptions& options) {
  // Switched off, the previous score gets no weight and eq. 7 returns eta.
  if (!options.enabled) return 0.0;
  options.validate();  // alpha > 0: eq. 6 divides by it
  requireFinite("previousScoreWeight", "eta", eta);
  requireFinite("previousScoreWeight", "eta_prev", eta_prev);
  return similarity_terms::previousWeight(eta, eta_prev, options.w_max, options.alpha);
}

double temporalScore(double eta, double eta_prev, const TemporalScoreOptions& options) {
  if (!options.enabled) return eta;  // ablation rows without the temporal score
  const double w_prev = previousScoreWeight(eta, eta_prev, options);
  return similarity_terms::temporal(eta, eta_prev, w_prev);  // eq. 7
}

CandidateScoreCombiner::CandidateScoreCombiner(const WordGroupOptions& groups,
                                               const DistributionOptions& distribution,
                                               const SimilarityOptions& similarity,
                                               const TemporalScoreOptions& temporal)
    : groups_(groups.enabled),
      distribution_(distribution.enabled),
      temporal_(temporal.enabled),
      l1_(similarity.lambda_1),
      l2_(similarity.lambda_2),
      w_max_(temporal.w_max),
      alpha_(temporal.alpha) {
  similarity.validate();
  if (temporal.enabled) temporal.validate();  // alpha > 0: eq. 6 divides by it
}

void CandidateScoreCombiner::failNotFinite(EntryId entry, double eta_sim, double eta_prev) {
  throw std::invalid_argument("candidate scores: entry " + std::to_string(entry) +
                              "'s score is not finite (eta_sim " + std::to_string(eta_sim) +
                              ", previous " + std::to_string(eta_prev) + ")");
}

}  // namespace bowg
