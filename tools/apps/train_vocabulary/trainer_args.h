// bowg_train_vocabulary's command line: the usage text, the options (tree,
// output, input, features) and their parser.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "bowg/features/feature_extractor.h"
#include "bowg/vocabulary/vocabulary_trainer.h"

namespace bowg {
namespace train_vocabulary_app {

extern const char* const kUsage;

struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct Args {
  TrainingOptions training;
  FeatureOptions features;
  std::string output;
  std::string format = "bowg";
  long max_images = 0, max_features = 0;
  std::vector<std::string> folders, bags;
  std::string image_topic = "/camera/image_raw";
  long every = 1;
};

/// Reads the options into `a`; false after printing the usage for
/// -h/--help. Throws std::invalid_argument (UsageError, a bad enum name, or
/// the options' own validate()).
bool parseArgs(int argc, char** argv, Args* a);

}  // namespace train_vocabulary_app
}  // namespace bowg
