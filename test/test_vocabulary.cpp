#include "test_vocabulary.h"

#include <unistd.h>

#include <vector>

#include "bowg/features/feature_extractor.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg/vocabulary/vocabulary_trainer.h"
#include "synthetic_world.h"

namespace bowg_ros {
namespace test {

std::string ensureTestVocabulary(const std::string& path) {
  if (access(path.c_str(), R_OK) == 0) return path;
  // Default features (GFTT + oriented ORB descriptors), the nodelet's default.
  const bowg::FeatureExtractor extractor{bowg::FeatureOptions()};
  std::vector<std::vector<bowg::Descriptor>> per_image;
  for (int i = 0; i < 30; ++i) {
    const cv::Mat world = makeWorld(320, 240, 1000 + i);  // seeds unused by the tests
    per_image.push_back(extractor.extract(world).descriptors);
  }
  bowg::TrainingOptions options;
  options.k = 8;
  options.L = 3;
  options.seed = 7;
  options.threads = 1;
  bowg::saveVocabulary(bowg::trainVocabulary(per_image, options), path);
  return path;
}

}  // namespace test
}  // namespace bowg_ros
