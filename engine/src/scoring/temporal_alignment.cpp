#include "bowg/scoring/temporal_alignment.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace bowg {
namespace {

// The first index in [from, size) where `before` is false, for a range
// partitioned by it (true, then false), found by doubling steps from
// `from`: O(log distance) where a cursor moves a little per call.
template <typename Before>
std::size_t gallop(std::size_t from, std::size_t size, Before before) {
  std::size_t step = 1;
  while (size - from > step && before(from + step)) {
    from += step;
    step *= 2;
  }
  const std::size_t end = std::min(size, from + step);
  // [from, end]: `before` holds at from (or from is the start) and fails at
  // end (or end is the size); a binary search finds the boundary.
  std::size_t lo = from, hi = end;
  while (lo < hi) {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (before(mid)) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return lo;
}

void requireValidMetres(double driven, double window_m) {
  if (!(std::isfinite(driven) && driven >= 0.0) || !(std::isfinite(window_m) && window_m >= 0.0)) {
    throw std::invalid_argument(
        "aligned previous score: driven and window_m must be finite and >= 0");
  }
}

}  // namespace

// One query's walk asked once: its cursors start at the beginning, so each
// gallop is a search of the whole range.
double alignedPreviousScore(const std::vector<std::pair<EntryId, double>>& previous, EntryId entry,
                            int missed, const TemporalScoreOptions& options) {
  return AlignedPreviousScores(previous, missed, options)(entry);
}

double alignedPreviousScoreInMetres(const std::vector<std::pair<EntryId, double>>& previous,
                                    const std::vector<double>& odometers, EntryId entry,
                                    double driven, double window_m) {
  return AlignedPreviousScores(previous, odometers, driven, window_m)(entry);
}

AlignedPreviousScores::AlignedPreviousScores(
    const std::vector<std::pair<EntryId, double>>& previous, int missed,
    const TemporalScoreOptions& options)
    : previous_(previous) {
  if (missed < 0) {
    throw std::invalid_argument("aligned previous score: missed must be >= 0 (got " +
                                std::to_string(missed) + ")");
  }
  steps_ = 1 + static_cast<std::int64_t>(missed);
  half_ = static_cast<std::int64_t>(options.alignment_window) * steps_;
}

AlignedPreviousScores::AlignedPreviousScores(
    const std::vector<std::pair<EntryId, double>>& previous, const std::vector<double>& odometers,
    double driven, double window_m)
    : previous_(previous), odometers_(&odometers), driven_(driven), window_m_(window_m) {
  requireValidMetres(driven, window_m);
}

double AlignedPreviousScores::operator()(EntryId entry) {
  if (entry < last_entry_) {
    throw std::invalid_argument("aligned previous score: entry " + std::to_string(entry) +
                                " after entry " + std::to_string(last_entry_) +
                                " (entries must be asked in ascending order)");
  }
  last_entry_ = entry;
  if (odometers_ == nullptr) {
    // Window: centre entry - (1 + missed), half-width alignment_window *
    // (1 + missed), in signed arithmetic (it may start before entry 0). Its
    // bounds only grow with the entry.
    const std::int64_t centre = static_cast<std::int64_t>(entry) - steps_;
    const std::int64_t last = centre + half_;
    if (last < 0) return 0.0;
    const std::int64_t first = std::max<std::int64_t>(0, centre - half_);
    return bestIn(static_cast<EntryId>(first), static_cast<EntryId>(last));
  }
  const std::vector<double>& odo = *odometers_;
  if (entry >= odo.size()) {
    throw std::invalid_argument("aligned previous score: entry " + std::to_string(entry) +
                                " beyond the " + std::to_string(odo.size()) + " odometers");
  }
  // Where the entry's place was when the previous query was taken, +/-
  // window_m. Odometers are non-decreasing, so the centre and both ends of
  // the window only grow with the entry.
  const double centre = odo[entry] - driven_;
  const double lo = centre - window_m_, hi = centre + window_m_;
  low_ = gallop(low_, odo.size(), [&](std::size_t i) { return odo[i] < lo; });
  high_ = gallop(std::max(high_, low_), odo.size(), [&](std::size_t i) { return !(hi < odo[i]); });
  if (low_ == high_) return 0.0;
  return bestIn(static_cast<EntryId>(low_), static_cast<EntryId>(high_ - 1));
}

double AlignedPreviousScores::bestIn(EntryId first, EntryId last) {
  previous_at_ = gallop(previous_at_, previous_.size(),
                        [&](std::size_t i) { return previous_[i].first < first; });
  // Scores are >= 0 (eqs. 2-9 of non-negative scores): 0 stands for "not
  // scored", as in eq. 7's reading (docs/method.md).
  double best = 0.0;
  for (std::size_t i = previous_at_; i < previous_.size() && previous_[i].first <= last; ++i) {
    best = std::max(best, previous_[i].second);
  }
  return best;
}

}  // namespace bowg
