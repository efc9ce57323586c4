// The synthetic corridor keyframes the pipeline and archive benchmarks share
// (engine/test/synthetic_corridor.h): a keyframe at a place of the corridor
// with ORB-like positions, the k=10 L=6 vocabulary trained on the corridor's
// views, and the pipe preset's options.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "bowg/detection/loop_detector.h"
#include "bowg/parameters/parameter_table.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_trainer.h"
#include "synthetic_corridor.h"

namespace bowg {
namespace bench {

/// The keyframe seen from `x` metres along `corridor`: 2 flipped bits per
/// descriptor and 0.5 px of noise, as revisits differ, with the positions on
/// ORB's pyramid grid (what the database packs).
inline KeyframeInput corridorKeyframe(const testing::Corridor& corridor, double x, double stamp,
                                      std::mt19937_64& rng) {
  KeyframeInput kf = testing::observeCorridor(corridor, x, stamp, rng, 2, 0.5);
  testing::placeOnOrbPyramid(&kf);
  return kf;
}

/// A k=10 L=6 vocabulary (TF-IDF, L1) trained by k-medians on the views of
/// `corridor` one metre apart from 5 m to `end_m`, as a vocabulary trained on
/// real images puts the views of one patch in one word. Deterministic.
inline Vocabulary trainCorridorVocabulary(const testing::Corridor& corridor, double end_m) {
  std::mt19937_64 rng(23);
  std::vector<std::vector<Descriptor>> images;
  for (double x = 5.0; x < end_m; x += 1.0) {
    images.push_back(testing::observeCorridor(corridor, x, 0.0, rng, 2, 0.5).features.descriptors);
  }
  TrainingOptions t;  // k = 10, L = 6, TF-IDF, L1
  t.threads = 2;
  return trainVocabulary(images, t);
}

/// The pipe preset's options (config/pipe.yaml) with the corridor's
/// recent-exclusion window and threshold. No odometry: the preset's windows
/// in keyframes apply. `recent_exclusion`: keyframes whose views still
/// overlap the query's (a view holds 8 m of wall); their trivial "loops"
/// would make every query run the verification.
inline LoopDetectorOptions corridorPresetOptions(int recent_exclusion) {
  LoopDetectorOptions o = loadParameterFile(std::string(BOWG_CONFIG_DIR) + "/pipe.yaml").detector;
  o.islands.recent_exclusion = recent_exclusion;
  // The corridor's consecutive keyframes see nearly the same wall, so a
  // revisit scores about what the previous keyframe does (eta ~1): the
  // preset's min_score, chosen on pipe sequences, would let none through.
  // The keyframes come without odometry: the preset's images-only margin
  // would raise their threshold above it again.
  o.islands.min_score = 1.0;
  o.islands.images_only_score_margin = 0.0;
  return o;
}

/// Adds one keyframe's stage times to `sum` (the benchmarks' per-keyframe
/// means divide it by the keyframes counted).
inline void addStageTimes(const StageTimings& t, StageTimings* sum) {
  sum->transform_ms += t.transform_ms;
  sum->word_groups_ms += t.word_groups_ms;
  sum->query_ms += t.query_ms;
  sum->islands_ms += t.islands_ms;
  sum->verification_ms += t.verification_ms;
  sum->total_ms += t.total_ms;
}

}  // namespace bench
}  // namespace bowg
