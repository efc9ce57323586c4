#include "bowg_pipe_sim/sequence_stats.h"

#include <algorithm>

namespace bowg {
namespace pipe_sim {

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

SequenceStats sequenceStats(const std::vector<FrameState>& frames,
                            const std::vector<int>& drive_starts) {
  SequenceStats s;
  s.frames = static_cast<int>(frames.size());
  if (frames.empty()) return s;
  s.driven_m = frames.back().odometer;
  std::vector<double> spacing;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    if (std::find(drive_starts.begin(), drive_starts.end(), static_cast<int>(i)) !=
        drive_starts.end()) {
      continue;
    }
    spacing.push_back(frames[i].distance - frames[i - 1].distance);
  }
  if (spacing.empty()) return s;
  const auto range = std::minmax_element(spacing.begin(), spacing.end());
  s.spacing_min_m = *range.first;
  s.spacing_max_m = *range.second;
  s.spacing_median_m = median(spacing);
  return s;
}

}  // namespace pipe_sim
}  // namespace bowg
