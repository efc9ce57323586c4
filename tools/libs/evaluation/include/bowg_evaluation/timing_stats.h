// Summary statistics of per-keyframe timings.
#pragma once

#include <vector>

namespace bowg {
namespace eval {

struct TimingStats {
  int count = 0;
  double mean = 0;
  /// Median: the middle value, or the mean of the two middle values.
  double median = 0;
  /// 95th percentile by nearest rank: the ceil(0.95 n)-th smallest value.
  double p95 = 0;
  double max = 0;
};

/// All zero for an empty input.
TimingStats computeTimingStats(std::vector<double> values);

}  // namespace eval
}  // namespace bowg
