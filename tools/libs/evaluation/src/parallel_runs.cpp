// Independent detector runs spread over threads (parallel_runs.h).
#include "bowg_evaluation/parallel_runs.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace bowg {
namespace eval {

std::vector<DetectorRun> runDetectorsInParallel(std::shared_ptr<const Vocabulary> vocabulary,
                                                const std::vector<RunRequest>& requests,
                                                const std::vector<FrameInput>& frames, int jobs,
                                                const ProgressCallback& progress,
                                                const RunMaps& maps) {
  if (jobs < 0) throw std::invalid_argument("runDetectorsInParallel: jobs must be >= 0");
  if (!maps.save.empty()) {
    throw std::invalid_argument("runDetectorsInParallel: runs side by side cannot save one map");
  }
  if (jobs == 0) jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<DetectorRun> runs(requests.size());
  std::atomic<std::size_t> next(0);
  std::mutex mutex;  // guards finished, error and the progress callback
  std::size_t finished = 0;
  std::exception_ptr error;
  auto worker = [&]() {
    for (std::size_t i = next++; i < requests.size(); i = next++) {
      try {
        runs[i] =
            runDetector(vocabulary, requests[i].options, frames, requests[i].name, nullptr, maps);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
        next = requests.size();  // the others stop after their current run
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      ++finished;
      if (progress) progress(finished, requests.size());
    }
  };
  const std::size_t threads = std::min(requests.size(), static_cast<std::size_t>(jobs));
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();  // the calling thread works too
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return runs;
}

std::vector<PrPoint> rerunPrCurve(std::shared_ptr<const Vocabulary> vocabulary,
                                  const LoopDetectorOptions& options,
                                  const std::vector<FrameInput>& frames, const GroundTruth& gt,
                                  const std::vector<double>& thresholds, int jobs) {
  std::vector<RunRequest> requests;
  for (double t : thresholds) {
    RunRequest r{"min_score " + std::to_string(t), options};
    r.options.islands.min_score = t;
    requests.push_back(r);
  }
  const std::vector<DetectorRun> runs =
      runDetectorsInParallel(std::move(vocabulary), requests, frames, jobs);
  std::vector<PrPoint> curve;
  for (const DetectorRun& run : runs) curve.push_back(operatingPoint(run, gt));
  return curve;
}

}  // namespace eval
}  // namespace bowg
