#include "bowg/temporal_alignment.h"

#include <algorithm>
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

}  // namespace bowg
