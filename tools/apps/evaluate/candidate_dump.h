// --dump-candidates: where the true revisit ranks among the candidates under
// each score of the method.
#pragma once

#include <memory>
#include <vector>

#include "bowg/detection/detection_options.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg_evaluation/detector_run.h"
#include "bowg_evaluation/ground_truth.h"
#include "evaluate_args.h"

namespace bowg {
namespace evaluate_app {

/// One run of the configured detector with every score on; writes the
/// per-query CSV to a.dump_candidates and prints the rank table. Returns 0.
int dumpCandidates(const Args& a, std::shared_ptr<const Vocabulary> vocabulary,
                   LoopDetectorOptions options, const std::vector<eval::FrameInput>& frames,
                   const eval::GroundTruth& gt);

}  // namespace evaluate_app
}  // namespace bowg
