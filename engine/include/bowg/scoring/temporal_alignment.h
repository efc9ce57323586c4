// Which earlier score the adaptive temporal score (eqs. 6-7) carries over.
//
// Eq. 7 reads eta(t-1, tj-1): the previous query's score of the entry just
// before the candidate. A true revisit follows that diagonal only when both
// passes advance one keyframe per keyframe; a pass at another speed or
// spacing, one that stops or backs up, drifts off it and loses the score it
// was building. The aligned reading takes the best previous score within a
// window around tj-1 (docs/method.md, "Aligned temporal score").
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/scoring/scoring_options.h"

namespace bowg {

/// eta(t-1, .) for candidate `entry`, from the previous scored query's
/// scores `previous` (sorted by entry id, unique ids). `missed` queries could
/// not be scored since then (0 = the previous scores are from query t-1).
/// Window: centre entry - (1 + missed), half-width
/// options.alignment_window * (1 + missed), clipped at entry 0; the result
/// is the largest score in it, 0 when none was scored there.
/// With alignment_window 0 and missed 0 this is eq. 7's eta(t-1, tj-1)
/// exactly (0 for entry 0). Throws std::invalid_argument for missed < 0.
double alignedPreviousScore(const std::vector<std::pair<EntryId, double>>& previous, EntryId entry,
                            int missed, const TemporalScoreOptions& options);

/// The same window in metres (TemporalScoreOptions::alignment_window_m):
/// the largest previous score among the entries whose odometer lies in
/// [odometers[entry] - driven - window_m, odometers[entry] - driven +
/// window_m], `driven` the metres from the previous scored query to this
/// one, `odometers` non-decreasing per entry (Database::odometers()).
/// 0 when none was scored there. Throws std::invalid_argument for an entry
/// beyond `odometers`, a negative or non-finite driven or window_m.
double alignedPreviousScoreInMetres(const std::vector<std::pair<EntryId, double>>& previous,
                                    const std::vector<double>& odometers, EntryId entry,
                                    double driven, double window_m);

/// alignedPreviousScore() (in keyframes) or alignedPreviousScoreInMetres()
/// for the candidates of one query asked in ascending entry order, as
/// Database::query returns them: the same values, found by cursors that
/// only move forward (galloping from the previous candidate's window)
/// instead of a search over the whole history for every candidate. A query
/// on a circuit driven lap after lap scores thousands of candidates. The
/// two functions above are this walk asked once. The vectors must outlive
/// this object and not change.
class AlignedPreviousScores {
 public:
  /// In keyframes. Throws std::invalid_argument for missed < 0.
  AlignedPreviousScores(const std::vector<std::pair<EntryId, double>>& previous, int missed,
                        const TemporalScoreOptions& options);
  /// In metres. Throws std::invalid_argument for a negative or non-finite
  /// driven or window_m.
  AlignedPreviousScores(const std::vector<std::pair<EntryId, double>>& previous,
                        const std::vector<double>& odometers, double driven, double window_m);

  /// The score for `entry`. Throws std::invalid_argument for an entry below
  /// the previous call's or (in metres) beyond the odometers.
  double operator()(EntryId entry);

 private:
  /// The largest previous score of the entries in [first, last].
  double bestIn(EntryId first, EntryId last);

  const std::vector<std::pair<EntryId, double>>& previous_;
  const std::vector<double>* odometers_ = nullptr;  ///< null: in keyframes
  std::int64_t steps_ = 1, half_ = 0;               ///< in keyframes
  double driven_ = 0.0, window_m_ = 0.0;            ///< in metres
  EntryId last_entry_ = 0;
  std::size_t previous_at_ = 0, low_ = 0, high_ = 0;  ///< the cursors
};

}  // namespace bowg
