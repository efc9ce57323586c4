// Shared by the loop detector's tests: the synthetic vocabulary, the
// options they start from and the corridor run (forward, then back over the
// same places).
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace testing {

inline std::shared_ptr<const Vocabulary> vocabulary() {
  static std::shared_ptr<const Vocabulary> v =
      std::make_shared<Vocabulary>(makeSyntheticVocabulary(10, 5, 7));
  return v;
}

inline LoopDetectorOptions defaultOptions() {
  LoopDetectorOptions o;
  o.geometric.direct_index_level = 3;
  return o;
}

// Forward along the corridor (keyframe i at x = i), then back (x = n - 0.5,
// n - 1.5, ...): the return pass revisits every place of the forward pass.
struct CorridorRun {
  std::vector<double> x;
  std::vector<LoopResult> results;
};

inline CorridorRun runCorridor(LoopDetector* det, bool with_return, int n = 60,
                               std::uint64_t seed = 3) {
  const Corridor c = makeCorridor(n + 10, 50, seed);
  std::mt19937_64 rng(seed + 100);
  CorridorRun run;
  for (int i = 0; i < n; ++i) run.x.push_back(i);
  if (with_return) {
    for (int i = 0; i < n; ++i) run.x.push_back(n - 0.5 - i);
  }
  for (std::size_t t = 0; t < run.x.size(); ++t) {
    run.results.push_back(
        det->process(observeCorridor(c, run.x[t], 1.0 + t, rng, /*bit_flips=*/2, /*noise=*/0.5)));
  }
  return run;
}

// Runs the revisit scenario with `o` and returns the statuses of the return pass.
inline std::vector<LoopStatus> returnStatuses(const LoopDetectorOptions& o) {
  LoopDetector det(vocabulary(), o);
  const CorridorRun run = runCorridor(&det, true);
  std::vector<LoopStatus> s;
  for (std::size_t t = 60; t < run.results.size(); ++t) s.push_back(run.results[t].status);
  return s;
}

inline bool contains(const std::vector<LoopStatus>& v, LoopStatus s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace testing
}  // namespace bowg
