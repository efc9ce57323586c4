// The detector runs of bowg_evaluate: one per row (the configuration, or
// each ablation row) at the configured threshold, timed alone, and the PR
// curve of each row (exact re-runs per threshold in parallel, or the final
// score of one run).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bowg/detection/detection_options.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg_evaluation/detector_run.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/metrics.h"
#include "evaluate_args.h"

namespace bowg {
namespace evaluate_app {

struct RowResult {
  eval::DetectorRun run;  // at the configured threshold
  eval::PrPoint at_threshold;
  std::vector<eval::PrPoint> curve;
  eval::PrPoint full_precision;
};

/// The thresholds of the sweep, highest first, with the configured one among
/// them: its run exists anyway, and a grid that steps over it would hide the
/// preset's own result.
std::vector<double> thresholdGrid(std::vector<double> requested, double configured);

/// Runs every row, each run starting on `maps` (the last row's saving the
/// map when maps.save names a file); with a ground truth (`gt` not null)
/// also its PR curve over `thresholds` and its recall at 100 % precision.
std::vector<RowResult> runRows(const Args& a, std::shared_ptr<const Vocabulary> vocabulary,
                               const LoopDetectorOptions& configured,
                               const std::vector<eval::FrameInput>& frames,
                               const eval::GroundTruth* gt, const std::vector<double>& thresholds,
                               const eval::RunMaps& maps);

}  // namespace evaluate_app
}  // namespace bowg
