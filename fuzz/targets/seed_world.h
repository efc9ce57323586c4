// The synthetic vocabulary, options and keyframes the database seeds are
// written with and the database target loads against (a database file only
// loads with the vocabulary it was built with).
#pragma once

#include <memory>
#include <random>

#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "synthetic_corridor.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace fuzz {

inline std::shared_ptr<const Vocabulary> seedVocabulary() {
  return std::make_shared<Vocabulary>(testing::makeSyntheticVocabulary(6, 3, 11));
}

inline LoopDetectorOptions seedOptions() {
  LoopDetectorOptions o;
  o.geometric.direct_index_level = 2;
  o.islands.recent_exclusion = 5;
  o.distribution.enabled = true;
  o.similarity.lambda_1 = 0.4;
  o.similarity.lambda_2 = 0.4;
  o.temporal_verification.hypotheses = 3;
  o.similarity.normaliser_floor = 1.0;
  return o;
}

/// Keyframe `i` of a corridor driven forward then back (revisits: the
/// saved state has chains, hypotheses and previous scores).
inline KeyframeInput seedKeyframe(int i) {
  static const testing::Corridor corridor = testing::makeCorridor(30, 20, 5);
  std::mt19937_64 rng(static_cast<std::uint64_t>(i) + 1);
  const double x = i < 15 ? i : 29.5 - i;
  KeyframeInput kf = testing::observeCorridor(corridor, x, 1.0 + i, rng, 2, 0.5);
  kf.odometer = 0.5 * i;
  kf.intrinsics.valid = true;
  kf.intrinsics.fx = kf.intrinsics.fy = 300.0;
  kf.intrinsics.cx = 160.0;
  kf.intrinsics.cy = 120.0;
  return kf;
}

}  // namespace fuzz
}  // namespace bowg
