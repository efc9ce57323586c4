// A small synthetic keyframe sequence with a known revisit, shared by the
// evaluation library's tests.
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "bowg_evaluation/detector_run.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace eval {
namespace testing_data {

/// 60 keyframes of random features; keyframes 40-49 repeat 10-19 exactly
/// (a revisit), so that whatever the detector finds there can be checked
/// against a ground truth 40+i: {10+i}.
inline std::vector<FrameInput> syntheticSequence() {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> x(40, 600), y(40, 440);
  std::vector<FrameInput> frames(60);
  for (int i = 0; i < 60; ++i) {
    FrameInput& f = frames[i];
    f.stamp = 0.1 * i;
    f.feature_ms = 1.0 + i;  // known values for the timing statistics
    f.feature_cpu_ms = 2.0 * (1.0 + i);
    if (i >= 40 && i < 50) {
      f.features = frames[i - 30].features;
      continue;
    }
    f.features.image_width = 640;
    f.features.image_height = 480;
    f.features.descriptors = testing::randomDescriptors(300, 100 + i);
    for (int k = 0; k < 300; ++k) {
      Keypoint p;
      p.x = x(rng);
      p.y = y(rng);
      p.size = 31;
      p.angle = 0;
      f.features.keypoints.push_back(p);
    }
  }
  return frames;
}

/// The vocabulary the synthetic sequence's descriptors are drawn for.
inline std::shared_ptr<const Vocabulary> syntheticSequenceVocabulary() {
  return std::make_shared<const Vocabulary>(testing::makeSyntheticVocabulary(6, 3));
}

/// Options under which the sequence's revisit closes: 5 recent keyframes
/// excluded, temporal verification of 1, the direct index at level 2.
inline LoopDetectorOptions syntheticSequenceOptions() {
  LoopDetectorOptions o;
  o.islands.recent_exclusion = 5;
  o.temporal_verification.k = 1;
  o.geometric.direct_index_level = 2;
  return o;
}

}  // namespace testing_data
}  // namespace eval
}  // namespace bowg
