// The keyframe_features input: upstream features in message layout
// (bowg::featuresFromArrays, which the ROS layer's fromMessage is), then,
// when accepted, three keyframes of them through a LoopDetector (word
// groups, query, verification compute with every value). Documented
// outcomes: features processed, or std::invalid_argument naming the field.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "bowg/detection/loop_detector.h"
#include "feature_bytes.h"
#include "seed_world.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::shared_ptr<const bowg::Vocabulary> vocabulary = bowg::fuzz::seedVocabulary();
  bowg::KeyframeInput input = bowg::fuzz::seedKeyframe(0);
  try {
    input.features = bowg::featuresFromArrays(bowg::fuzz::featureArraysFromBytes(data, size),
                                              bowg::FeatureOptions());
  } catch (const std::invalid_argument&) {
    return 0;
  }
  bowg::LoopDetectorOptions options = bowg::fuzz::seedOptions();
  options.islands.recent_exclusion = 0;  // let the repeats be matched
  bowg::LoopDetector detector(vocabulary, options);
  for (int i = 0; i < 3; ++i) {
    input.stamp = 1.0 + i;
    input.odometer = 0.5 * i;
    try {
      detector.process(input);
    } catch (const std::invalid_argument&) {
      return 0;
    }
  }
  return 0;
}
