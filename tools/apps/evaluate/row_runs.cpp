// The detector runs of bowg_evaluate (row_runs.h).
#include "row_runs.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "bowg_evaluation/parallel_runs.h"
#include "console_output.h"

namespace bowg {
namespace evaluate_app {

using namespace bowg::eval;

namespace {

bool same(double a, double b) { return std::abs(a - b) < 1e-12; }

// The exact PR curves: every (row, other threshold) run, side by side. Runs in
// the order row by row, threshold by threshold (highest first).
std::vector<DetectorRun> sweepRuns(const Args& a, std::shared_ptr<const Vocabulary> vocabulary,
                                   const std::vector<std::string>& rows,
                                   const std::vector<LoopDetectorOptions>& row_options,
                                   const std::vector<FrameInput>& frames,
                                   const std::vector<double>& thresholds, double configured,
                                   const RunMaps& maps) {
  std::vector<RunRequest> requests;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (double t : thresholds) {
      if (same(t, configured)) continue;
      RunRequest q{rows[i], row_options[i]};
      q.options.islands.min_score = t;
      requests.push_back(q);
    }
  }
  ProgressBar bar("sweep (" + std::to_string(requests.size()) + " runs)", a.quiet);
  return runDetectorsInParallel(vocabulary, requests, frames, a.jobs, std::ref(bar), maps);
}

}  // namespace

std::vector<double> thresholdGrid(std::vector<double> thresholds, double configured) {
  if (std::none_of(thresholds.begin(), thresholds.end(),
                   [configured](double t) { return same(t, configured); })) {
    thresholds.push_back(configured);
    std::sort(thresholds.begin(), thresholds.end(), std::greater<double>());
  }
  return thresholds;
}

std::vector<RowResult> runRows(const Args& a, std::shared_ptr<const Vocabulary> vocabulary,
                               const LoopDetectorOptions& configured,
                               const std::vector<FrameInput>& frames, const GroundTruth* gt,
                               const std::vector<double>& thresholds, const RunMaps& maps) {
  RunMaps load_only = maps;
  load_only.save.clear();
  const std::vector<std::string> rows = a.ablation ? a.rows : std::vector<std::string>{"bowg"};
  const double threshold = configured.islands.min_score;
  std::vector<RowResult> results;
  std::vector<LoopDetectorOptions> row_options;
  // 1. One run per row at the configured threshold, alone on the machine:
  // its timings are the ones reported.
  for (const std::string& row : rows) {
    row_options.push_back(a.ablation ? LoopDetectorOptions::ablation(row, configured) : configured);
    RowResult r;
    ProgressBar bar(row + " @" + fmt("%.2f", threshold), a.quiet);
    const bool last = results.size() + 1 == rows.size();
    r.run = runDetector(vocabulary, row_options.back(), frames, row, std::ref(bar),
                        last ? maps : load_only);
    if (gt) r.at_threshold = operatingPoint(r.run, *gt);
    results.push_back(std::move(r));
  }
  if (!gt) return results;
  // 2. The PR curves.
  std::vector<DetectorRun> sweep_runs;
  if (a.sweep == "rerun") {
    sweep_runs =
        sweepRuns(a, vocabulary, rows, row_options, frames, thresholds, threshold, load_only);
  }
  std::size_t next_sweep_run = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    RowResult& r = results[i];
    if (a.sweep == "rerun") {
      for (double t : thresholds) {
        r.curve.push_back(same(t, threshold) ? r.at_threshold
                                             : operatingPoint(sweep_runs[next_sweep_run++], *gt));
      }
    } else {
      LoopDetectorOptions o = row_options[i];
      o.islands.min_score = thresholds.back();  // the lowest
      ProgressBar b(rows[i] + " @" + fmt("%.2f", o.islands.min_score), a.quiet);
      const DetectorRun low =
          same(o.islands.min_score, threshold)
              ? r.run
              : runDetector(vocabulary, o, frames, rows[i], std::ref(b), load_only);
      r.curve = precisionRecallCurve(detectionsOf(low), *gt);
    }
    r.full_precision = recallAtFullPrecision(r.curve);
  }
  return results;
}

}  // namespace evaluate_app
}  // namespace bowg
