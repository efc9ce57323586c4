// What a generated sequence looks like in numbers, for the generator's
// summary and the ground-truth header: with a varying speed the frame
// spacing is no longer speed / rate, and a detector's keyframe settings
// (docs/pipe_sequence.md) depend on it.
#pragma once

#include <vector>

#include "bowg_pipe_sim/pipe_sequence.h"

namespace bowg {
namespace pipe_sim {

struct SequenceStats {
  int frames = 0;
  double driven_m = 0;  ///< odometer of the last frame (backing up counts)
  /// Signed change of the position along the route between consecutive
  /// frames (negative while backing up); all 0 for fewer than two frames.
  double spacing_min_m = 0, spacing_median_m = 0, spacing_max_m = 0;
};

/// `drive_starts`: positions in `frames` where another drive begins (the
/// next mission of a re-inspection, its route position from 0 again); the
/// spacing is measured within drives only.
SequenceStats sequenceStats(const std::vector<FrameState>& frames,
                            const std::vector<int>& drive_starts = {});

/// The upper median (element size / 2 of the sorted values), 0 when empty.
double median(std::vector<double> values);

}  // namespace pipe_sim
}  // namespace bowg
