#include "bowg/scoring/temporal_alignment.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace bowg {

double alignedPreviousScore(const std::vector<std::pair<EntryId, double>>& previous, EntryId entry,
                            int missed, const TemporalScoreOptions& options) {
  if (missed < 0) {
    throw std::invalid_argument("alignedPreviousScore: missed must be >= 0 (got " +
                                std::to_string(missed) + ")");
  }
  // Signed arithmetic: the window may start before entry 0.
  const std::int64_t steps = 1 + static_cast<std::int64_t>(missed);
  const std::int64_t centre = static_cast<std::int64_t>(entry) - steps;
  const std::int64_t half = static_cast<std::int64_t>(options.alignment_window) * steps;
  const std::int64_t last = centre + half;
  if (last < 0) return 0.0;
  const std::int64_t first = std::max<std::int64_t>(0, centre - half);
  auto it = std::lower_bound(
      previous.begin(), previous.end(), static_cast<EntryId>(first),
      [](const std::pair<EntryId, double>& p, EntryId id) { return p.first < id; });
  // Scores are >= 0 (eqs. 2-9 of non-negative scores): 0 stands for "not
  // scored", as in eq. 7's reading (docs/method.md).
  double best = 0.0;
  for (; it != previous.end() && static_cast<std::int64_t>(it->first) <= last; ++it) {
    best = std::max(best, it->second);
  }
  return best;
}

double alignedPreviousScoreInMetres(const std::vector<std::pair<EntryId, double>>& previous,
                                    const std::vector<double>& odometers, EntryId entry,
                                    double driven, double window_m) {
  if (entry >= odometers.size()) {
    throw std::invalid_argument("alignedPreviousScoreInMetres: entry " + std::to_string(entry) +
                                " beyond the " + std::to_string(odometers.size()) + " odometers");
  }
  if (!(std::isfinite(driven) && driven >= 0.0) || !(std::isfinite(window_m) && window_m >= 0.0)) {
    throw std::invalid_argument("alignedPreviousScoreInMetres: driven and window_m must be finite "
                                "and >= 0");
  }
  // Where the entry's place was when the previous query was taken.
  const double centre = odometers[entry] - driven;
  const auto lo = std::lower_bound(odometers.begin(), odometers.end(), centre - window_m);
  const auto hi = std::upper_bound(lo, odometers.end(), centre + window_m);
  if (lo == hi) return 0.0;
  const EntryId first = static_cast<EntryId>(lo - odometers.begin());
  const EntryId last = static_cast<EntryId>(hi - odometers.begin()) - 1;
  auto it = std::lower_bound(
      previous.begin(), previous.end(), first,
      [](const std::pair<EntryId, double>& p, EntryId id) { return p.first < id; });
  double best = 0.0;
  for (; it != previous.end() && it->first <= last; ++it) best = std::max(best, it->second);
  return best;
}

}  // namespace bowg
