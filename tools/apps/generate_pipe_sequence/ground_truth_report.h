// The loop ground truth of a generated sequence: computed from the driven
// poses, written with a header that records how the sequence was made
// (options, frame spacing, odometry, tolerances), and summarised for the
// console.
#pragma once

#include <string>
#include <vector>

#include "bowg_evaluation/ground_truth.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "generator_args.h"

namespace bowg {
namespace generate_pipe_sequence_app {

struct GroundTruthSummary {
  int positives = 0;           ///< queries with a revisit
  double median_roll_deg = 0;  ///< median roll difference between matching frames
  std::string spacing;         ///< metres driven and frame spacing, one line
  std::string odometry;        ///< the odometry's options and end-point drift, one line
};

/// Computes the ground truth of `frames` (all missions, one after the
/// other, the first frame of each in `mission_starts`) from their poses
/// `travel` and writes it to args.gt; `odometry_drift_m` is the distance
/// between the last frame's odometry and true positions.
GroundTruthSummary writeSequenceGroundTruth(const Args& args,
                                            const std::vector<pipe_sim::FrameState>& frames,
                                            const std::vector<int>& mission_starts,
                                            const std::vector<eval::TravelPose>& travel,
                                            double odometry_drift_m);

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
