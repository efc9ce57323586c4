// What bowg_evaluate writes: summary.txt (also printed), per-row keyframe and
// detection CSVs, time versus database size, PR curves and their plot.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "bowg_evaluation/ground_truth.h"
#include "evaluate_args.h"
#include "row_runs.h"

namespace bowg {
namespace evaluate_app {

/// What the summary says about the run's inputs beyond the command line.
struct RunInputs {
  std::size_t frames = 0;  ///< the live frames run
  std::string odometry;    ///< the acceptance the odometry gives (one line)
  /// The reference maps (--map): their keyframes (entries 0..map_entries-1)
  /// and a line naming them and their missions ("" without maps).
  std::size_t map_entries = 0;
  std::string maps;
};

/// Writes every output into a.output and prints the summary. `gt` is null
/// without a ground truth (counts only).
void writeReport(const Args& a, const std::vector<RowResult>& results, const RunInputs& inputs,
                 const eval::GroundTruth* gt, const std::vector<double>& thresholds,
                 double threshold);

}  // namespace evaluate_app
}  // namespace bowg
