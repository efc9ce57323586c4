// validate() of the scoring stage's options (scoring_options.h).
#include "bowg/scoring/scoring_options.h"

#include "bowg/core/errors.h"
#include "bowg/core/validation.h"

namespace bowg {
namespace {

// Rounding slack for "lambda_1 + lambda_2 <= 1" (e.g. 0.1 + 0.9).
const double kSumTolerance = 1e-12;

// m above this only costs memory and time: one bin per degree is already finer
// than the angular precision of any corner detector.
const int kMaxFanBins = 360;

}  // namespace

using namespace check;

void WordGroupOptions::validate() const {
  requireFinitePositive("word_groups.radius_scale", radius_scale);
}

void DistributionOptions::validate() const {
  requireIntInRange("distribution.fan_bins", fan_bins, 1, kMaxFanBins);
}

void SimilarityOptions::validate() const {
  requireUnitInterval("similarity.lambda_1", lambda_1);
  requireUnitInterval("similarity.lambda_2", lambda_2);
  // Eq. 9 gives eta_d the weight 1 - l1 - l2, which must not be negative.
  // Checked even with the distribution off, as the header documents, so that
  // switching the distribution on live can never make the options invalid.
  if (lambda_1 + lambda_2 > 1.0 + kSumTolerance) {
    throw InvalidParameter("similarity.lambda_1 + similarity.lambda_2 must be <= 1 (got " +
                           str(lambda_1) + " + " + str(lambda_2) + ")");
  }
  requireFiniteAtLeast("similarity.min_word_normaliser", min_word_normaliser, 0.0);
  requireFiniteAtLeast("similarity.min_group_normaliser", min_group_normaliser, 0.0);
  requireFiniteAtLeast("similarity.min_distribution_normaliser", min_distribution_normaliser, 0.0);
  requireFiniteAtLeast("similarity.normaliser_floor", normaliser_floor, 0.0);
  requireIntAtLeast("similarity.normaliser_window", normaliser_window, 1);
  requireFiniteAtLeast("similarity.normaliser_distance_m", normaliser_distance_m, 0.0);
  requireIntAtLeast("similarity.normaliser_lookback", normaliser_lookback, 0);
  requireFiniteAtLeast("similarity.normaliser_lookback_ratio", normaliser_lookback_ratio, 1.0);
}

void TemporalScoreOptions::validate() const {
  // w_max = 1 would let the previous score replace the current one entirely
  // when both are equal (eq. 6 -> w_prev = 1), freezing the score.
  if (!(w_max >= 0.0 && w_max < 1.0)) fail("temporal_score.w_max", "must be in [0, 1)", str(w_max));
  requireFinitePositive("temporal_score.alpha", alpha);
  requireIntAtLeast("temporal_score.alignment_window", alignment_window, 0);
  requireIntAtLeast("temporal_score.max_missed_queries", max_missed_queries, 0);
  requireFiniteAtLeast("temporal_score.alignment_window_m", alignment_window_m, 0.0);
}

}  // namespace bowg
