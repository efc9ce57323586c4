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

/// Writes every output into a.output and prints the summary, which names the
/// odometry the run had (`odometry`, one line). `gt` is null without a ground
/// truth (counts only).
void writeReport(const Args& a, const std::vector<RowResult>& results, std::size_t frames,
                 const std::string& odometry, const eval::GroundTruth* gt,
                 const std::vector<double>& thresholds, double threshold);

}  // namespace evaluate_app
}  // namespace bowg
