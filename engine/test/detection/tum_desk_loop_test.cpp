// Real imagery: the 10 TUM RGB-D desk frames of ../shared/data/tum_desk10
// (frames 1 and 10 view the same desk, the others move away from it and back).
// With ORB features and the shared DBoW3 ORB vocabulary (k=10, L=5), the whole
// pipeline must close exactly one loop, 10 -> 1, through geometric
// verification, and none between the other frames. Skips where the shared
// data is absent.
#include <sys/stat.h>

#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bowg/detection/loop_detector.h"
#include "bowg/features/feature_extractor.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"

namespace bowg {
namespace {

bool exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

TEST(TumDeskLoop, ClosesFrameTenOnFrameOneOnly) {
  const std::string data = BOWG_SHARED_DATA_DIR;
  const std::string voc_path = data + "/vocabularies/dbow3_orb_k10L5_vocabulary.yml.gz";
  if (!exists(data + "/tum_desk10/1.png") || !exists(voc_path)) {
    GTEST_SKIP() << "shared TUM desk frames or DBoW3 vocabulary absent under " << data;
  }
  auto vocabulary = std::make_shared<Vocabulary>(loadVocabulary(voc_path));

  FeatureOptions fo;
  fo.detector = FeatureOptions::Detector::kOrb;  // the paper's public-dataset setting
  const FeatureExtractor extractor(fo);

  // Ten frames far apart: consecutive frames share little, so the previous-
  // keyframe normaliser is no gate here, nor the temporal parts (one revisit).
  LoopDetectorOptions o;
  o.distribution.enabled = false;
  o.temporal_score.enabled = false;
  o.temporal_verification.k = 0;
  o.islands.recent_exclusion = 3;
  o.similarity.min_word_normaliser = 0.0;
  o.similarity.min_group_normaliser = 0.0;
  o.geometric.direct_index_level = 3;
  LoopDetector detector(vocabulary, o);

  int loops = 0;
  for (int i = 1; i <= 10; ++i) {
    const cv::Mat image =
        cv::imread(data + "/tum_desk10/" + std::to_string(i) + ".png", cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(image.empty()) << "frame " << i;
    KeyframeInput kf;
    kf.stamp = i;
    kf.features = extractor.extract(image);
    const LoopResult r = detector.process(kf);
    if (r.status == LoopStatus::kLoopDetected) {
      ++loops;
      EXPECT_EQ(i, 10) << "false loop from frame " << i << " to " << r.match_id + 1;
      EXPECT_EQ(r.match_id, 0u) << "frame 10 must close on frame 1";
      EXPECT_GE(r.inliers, o.geometric.min_inliers);
    }
  }
  EXPECT_EQ(loops, 1);
}

}  // namespace
}  // namespace bowg
