#include "bowg_evaluation/timing_stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace bowg {
namespace eval {

TimingStats computeTimingStats(std::vector<double> values) {
  TimingStats s;
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  s.count = static_cast<int>(n);
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * n));
  s.p95 = values[std::max<std::size_t>(rank, 1) - 1];
  s.max = values.back();
  return s;
}

}  // namespace eval
}  // namespace bowg
