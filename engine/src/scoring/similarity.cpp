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
  const double l1 = similarity.lambda_1;
  const double l2 = similarity.lambda_2;
  if (groups.enabled && distribution.enabled) {
    requireFinite("combineSimilarity", "eta_g", eta_g);
    requireFinite("combineSimilarity", "eta_d", eta_d);
    return l1 * eta_w + l2 * eta_g + (1.0 - l1 - l2) * eta_d;  // eq. 9
  }
  if (groups.enabled) {
    requireFinite("combineSimilarity", "eta_g", eta_g);
    return l1 * eta_w + (1.0 - l1) * eta_g;  // eq. 5
  }
  if (distribution.enabled) {
    // Not in the paper (it never runs the distribution without groups): eq. 5
    // with eta_d in place of eta_g, so that lambda_1 keeps its meaning.
    requireFinite("combineSimilarity", "eta_d", eta_d);
    return l1 * eta_w + (1.0 - l1) * eta_d;
  }
  return eta_w;  // pure bag of words (ablation row "bow")
}

double previousScoreWeight(double eta, double eta_prev, const TemporalScoreOptions& options) {
  // Switched off, the previous score gets no weight and eq. 7 returns eta.
  if (!options.enabled) return 0.0;
  options.validate();  // alpha > 0: eq. 6 divides by it
  requireFinite("previousScoreWeight", "eta", eta);
  requireFinite("previousScoreWeight", "eta_prev", eta_prev);
  // Eq. 6: the previous score weighs less the more it differs from the current
  // one, so a single transient spike (or dip) does not carry over.
  const double d = (eta - eta_prev) / options.alpha;
  return options.w_max / (1.0 + d * d);
}

double temporalScore(double eta, double eta_prev, const TemporalScoreOptions& options) {
  if (!options.enabled) return eta;  // ablation rows without the temporal score
  const double w_prev = previousScoreWeight(eta, eta_prev, options);
  return w_prev * eta_prev + (1.0 - w_prev) * eta;  // eq. 7
}

}  // namespace bowg
