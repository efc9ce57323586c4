// bowg_train_vocabulary: trains a vocabulary tree (paper Sec. III-A) from the
// images of folders and/or rosbags (sensor_msgs/Image or CompressedImage on
// one topic). Gathering the images and extracting their features live here;
// the training itself is the engine's bowg::trainVocabulary(). Bag images
// are read through libs/bag_reading (bag_images.h), as the nodelet reads them.
//
// The pieces: trainer_args (command line), image_sources (which images),
// descriptor_extraction (their features), progress_bar; here the training,
// the saving and the exit codes (2: bad command line, 1: failure).
#include <cstdio>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg/vocabulary/vocabulary_trainer.h"
#include "descriptor_extraction.h"
#include "image_sources.h"
#include "progress_bar.h"
#include "trainer_args.h"

namespace bowg {
namespace train_vocabulary_app {
namespace {

/// Everything after the command line; returns the exit code, throws on a
/// failure.
int train(const Args& a) {
  const VocabularyFormat out_format = vocabularyFormatFromString(a.format);
  std::vector<ImageSource> images = gatherImageSources(a);
  if (images.empty()) {
    std::cerr << "error: no .png/.jpg/.jpeg image found in the given folders\n";
    return 1;
  }
  images = pickEvenly(std::move(images), a.max_images);
  const TrainingDescriptors d = extractDescriptors(images, a);
  std::fprintf(stderr, "\n%zu images (%zu skipped%s%s), %zu descriptors\n", d.per_image.size(),
               d.skipped.total(), d.skipped.total() > 0 ? ": " : "", d.skipped.summary().c_str(),
               d.total);
  const Vocabulary v = trainVocabulary(
      d.per_image, a.training,
      [](double f, const std::string& stage) { progressBar(0.2 + 0.8 * f, stage); });
  saveVocabulary(v, a.output, out_format);
  std::fprintf(stderr, "wrote %s: k=%d L=%d nodes=%zu words=%zu fingerprint %016llx\n",
               a.output.c_str(), v.branching(), v.depth(), v.nodeCount(), v.wordCount(),
               static_cast<unsigned long long>(v.fingerprint()));
  return 0;
}

}  // namespace
}  // namespace train_vocabulary_app
}  // namespace bowg

int main(int argc, char** argv) {
  using namespace bowg::train_vocabulary_app;
  Args args;
  try {
    if (!parseArgs(argc, argv, &args)) return 0;
  } catch (const std::invalid_argument& e) {  // UsageError, InvalidParameter, bad enum names
    std::cerr << "error: " << e.what() << "\n\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {  // --config: the file cannot be read
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  try {
    return train(args);
  } catch (const std::exception& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    return 1;
  }
}
