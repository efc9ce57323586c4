// Normalisation (eqs. 2, 4), combination (eqs. 5, 9) and the adaptive
// temporal score (eqs. 6-7) of the BoWG similarity.
#pragma once

#include <cmath>

#include "bowg/core/types.h"
#include "bowg/scoring/scoring_options.h"

namespace bowg {

/// The formulas of eqs. 5/9 and 6-7 without any check: the checked
/// functions below and CandidateScoreCombiner share them, so both give the
/// same values bit for bit.
namespace similarity_terms {
inline double combined(double eta_w, double eta_g, double eta_d, bool groups, bool distribution,
                       double l1, double l2) {
  if (groups && distribution) return l1 * eta_w + l2 * eta_g + (1.0 - l1 - l2) * eta_d;  // eq. 9
  if (groups) return l1 * eta_w + (1.0 - l1) * eta_g;                                    // eq. 5
  // Not in the paper (it never runs the distribution without groups): eq. 5
  // with eta_d in place of eta_g, so that lambda_1 keeps its meaning.
  if (distribution) return l1 * eta_w + (1.0 - l1) * eta_d;
  return eta_w;  // pure bag of words (ablation row "bow")
}
/// Eq. 6: the previous score weighs less the more it differs from the
/// current one, so a single transient spike (or dip) does not carry over.
inline double previousWeight(double eta, double eta_prev, double w_max, double alpha) {
  const double d = (eta - eta_prev) / alpha;
  return w_max / (1.0 + d * d);
}
/// Eq. 7.
inline double temporal(double eta, double eta_prev, double w_prev) {
  return w_prev * eta_prev + (1.0 - w_prev) * eta;
}
}  // namespace similarity_terms

/// eta = score / normaliser (normaliser = score against the previous
/// keyframe, > 0 by the caller's check).
inline double normaliseScore(double score, double normaliser) { return score / normaliser; }

/// Combined similarity eta_sim:
///  - groups on,  distribution on : l1*eta_w + l2*eta_g + (1-l1-l2)*eta_d (eq. 9)
///  - groups on,  distribution off: l1*eta_w + (1-l1)*eta_g               (eq. 5)
///  - groups off, distribution on : l1*eta_w + (1-l1)*eta_d  (eq. 5 with eta_d)
///  - groups off, distribution off: eta_w                    (pure bag of words)
double combineSimilarity(double eta_w, double eta_g, double eta_d, const WordGroupOptions& groups,
                         const DistributionOptions& distribution,
                         const SimilarityOptions& similarity);

/// Eq. 6: w_prev = w_max / (1 + ((eta - eta_prev) / alpha)^2).
double previousScoreWeight(double eta, double eta_prev, const TemporalScoreOptions& options);

/// Eq. 7: eta_temp = w_prev * eta_prev + (1 - w_prev) * eta. eta_prev is the
/// previous query's (temporal) score of entry tj-1, 0 where it was not scored.
double temporalScore(double eta, double eta_prev, const TemporalScoreOptions& options);

/// combineSimilarity then temporalScore for the many candidates of one query
/// (a large map's query scores ~10^5): the options are checked once, here,
/// and each candidate's final score once (a score that is not finite makes
/// it not finite, whichever it was). Same values as the checked functions.
class CandidateScoreCombiner {
 public:
  /// Throws std::invalid_argument for invalid options.
  CandidateScoreCombiner(const WordGroupOptions& groups, const DistributionOptions& distribution,
                         const SimilarityOptions& similarity, const TemporalScoreOptions& temporal);
  double similarity(double eta_w, double eta_g, double eta_d) const {
    return similarity_terms::combined(eta_w, eta_g, eta_d, groups_, distribution_, l1_, l2_);
  }
  /// Eqs. 6-7 on eta_sim; throws std::invalid_argument naming `entry` when
  /// the result is not finite.
  double temporal(double eta_sim, double eta_prev, EntryId entry) const {
    const double eta =
        temporal_ ? similarity_terms::temporal(
                        eta_sim, eta_prev,
                        similarity_terms::previousWeight(eta_sim, eta_prev, w_max_, alpha_))
                  : eta_sim;
    if (!std::isfinite(eta)) failNotFinite(entry, eta_sim, eta_prev);
    return eta;
  }

 private:
  [[noreturn]] static void failNotFinite(EntryId entry, double eta_sim, double eta_prev);
  bool groups_, distribution_, temporal_;
  double l1_, l2_, w_max_, alpha_;
};

}  // namespace bowg
