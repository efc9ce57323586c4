#include "bowg_evaluation/stamp_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace bowg {
namespace eval {

StampIndex::StampIndex(const std::vector<std::int64_t>& stamps_ns) : frames_(stamps_ns.size()) {
  sorted_.reserve(stamps_ns.size());
  for (std::size_t n = 0; n < stamps_ns.size(); ++n) {
    sorted_.emplace_back(stamps_ns[n], static_cast<int>(n));
  }
  // Sorting (stamp, frame) puts the first frame of a repeated stamp first;
  // unique() on the stamp alone then keeps exactly that one.
  std::sort(sorted_.begin(), sorted_.end());
  sorted_.erase(
      std::unique(sorted_.begin(), sorted_.end(),
                  [](const std::pair<std::int64_t, int>& a, const std::pair<std::int64_t, int>& b) {
                    return a.first == b.first;
                  }),
      sorted_.end());
}

int StampIndex::find(std::int64_t stamp_ns, std::int64_t tolerance_ns) const {
  if (tolerance_ns < 0) {
    throw std::invalid_argument("StampIndex::find: tolerance_ns must be >= 0");
  }
  if (sorted_.empty()) return -1;
  const auto after = std::lower_bound(
      sorted_.begin(), sorted_.end(), stamp_ns,
      [](const std::pair<std::int64_t, int>& e, std::int64_t s) { return e.first < s; });
  // Candidates: the first stamp >= the query and the one before it. The
  // differences are taken in unsigned arithmetic so that extreme stamps do
  // not overflow.
  auto distance = [stamp_ns](std::int64_t s) {
    return s >= stamp_ns ? static_cast<std::uint64_t>(s) - static_cast<std::uint64_t>(stamp_ns)
                         : static_cast<std::uint64_t>(stamp_ns) - static_cast<std::uint64_t>(s);
  };
  int best = -1;
  std::uint64_t best_distance = std::numeric_limits<std::uint64_t>::max();
  if (after != sorted_.begin()) {
    best = std::prev(after)->second;
    best_distance = distance(std::prev(after)->first);
  }
  if (after != sorted_.end() && distance(after->first) < best_distance) {
    best = after->second;
    best_distance = distance(after->first);
  }
  return best_distance <= static_cast<std::uint64_t>(tolerance_ns) ? best : -1;
}

std::int64_t StampIndex::safeTolerance(std::int64_t cap_ns) const {
  std::int64_t tolerance = cap_ns;
  for (std::size_t i = 1; i < sorted_.size(); ++i) {
    // Strictly less than half the gap (2 t < gap, i.e. t <= (gap - 1) / 2):
    // then no stamp is within t of two frames.
    tolerance = std::min(tolerance, (sorted_[i].first - sorted_[i - 1].first - 1) / 2);
  }
  return std::max<std::int64_t>(tolerance, 0);
}

std::int64_t secondsToNanoseconds(double seconds) {
  if (!std::isfinite(seconds) || std::abs(seconds) > 9.2e9) {
    throw std::invalid_argument("secondsToNanoseconds: stamp out of range");
  }
  return static_cast<std::int64_t>(std::llround(seconds * 1e9));
}

}  // namespace eval
}  // namespace bowg
