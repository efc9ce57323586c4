// Normalisation (eqs. 2, 4), combination (eqs. 5, 9) and the adaptive
// temporal score (eqs. 6-7) of the BoWG similarity.
#pragma once

#include "bowg/scoring/scoring_options.h"

namespace bowg {

/// eta = score / normaliser (normaliser = score against the previous
/// keyframe, > 0 by the caller's check).
inline double normaliseScore(double score, double normaliser) { return score / normaliser; }

/// Combined similarity eta_sim:
///  - groups on,  distribution on : l1*eta_w + l2*eta_g + (1-l1-l2)*eta_d (eq. 9)
///  - groups on,  distribution off: l1*eta_w + (1-l1)*eta_g               (eq. 5)
///  - groups off, distribution on : l1*eta_w + (1-l1)*eta_d  (eq. 5 with eta_d)
///  - groups off, distribution off: eta_w                    (pure bag of words)
double combineSimilarity(double eta_w, double eta_g, double eta_d,
                         const WordGroupOptions& groups, const DistributionOptions& distribution,
                         const SimilarityOptions& similarity);

/// Eq. 6: w_prev = w_max / (1 + ((eta - eta_prev) / alpha)^2).
double previousScoreWeight(double eta, double eta_prev, const TemporalScoreOptions& options);

/// Eq. 7: eta_temp = w_prev * eta_prev + (1 - w_prev) * eta. eta_prev is the
/// previous query's (temporal) score of entry tj-1, 0 where it was not scored.
double temporalScore(double eta, double eta_prev, const TemporalScoreOptions& options);

}  // namespace bowg
