// Several detector runs over the same keyframes at once: the exact PR curve
// re-runs the detector once per min_score (islands and the temporal
// verification change with the threshold, so a sweep over the final score of
// one run is not the same curve), for every ablation row. The runs are
// independent - each has its own LoopDetector; the vocabulary and the frames
// are shared read-only - so they spread over the cores.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg_evaluation/detector_run.h"

namespace bowg {
namespace eval {

struct RunRequest {
  std::string name;
  LoopDetectorOptions options;
};

/// Runs every request on up to `jobs` threads (>= 1; 0 = one per hardware
/// thread) and returns the runs in request order. `progress` is called with
/// (finished runs, total runs), from one thread at a time. The per-stage
/// timings of runs made side by side include the contention between them:
/// measure timing with runDetector() alone. Rethrows the first exception a
/// run threw, after every thread has stopped. Every run starts from `maps`
/// (std::invalid_argument when it names a file to save: one run saves).
std::vector<DetectorRun> runDetectorsInParallel(std::shared_ptr<const Vocabulary> vocabulary,
                                                const std::vector<RunRequest>& requests,
                                                const std::vector<FrameInput>& frames, int jobs,
                                                const ProgressCallback& progress = nullptr,
                                                const RunMaps& maps = RunMaps());

/// The exact PR curve of one options set: one run per min_score in
/// `thresholds`, each evaluated against `gt` (points in the thresholds' order).
std::vector<PrPoint> rerunPrCurve(std::shared_ptr<const Vocabulary> vocabulary,
                                  const LoopDetectorOptions& options,
                                  const std::vector<FrameInput>& frames, const GroundTruth& gt,
                                  const std::vector<double>& thresholds, int jobs);

}  // namespace eval
}  // namespace bowg
