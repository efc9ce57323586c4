// The features bowg_train_vocabulary trains on: every image source read
// (files as grey images, bag messages through libs/bag_reading, bag_images.h,
// as the nodelet reads them) and its descriptors extracted, the strongest
// --max-features-per-image of them kept.
#pragma once

#include <cstddef>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/features/image_check.h"
#include "image_sources.h"
#include "trainer_args.h"

namespace bowg {
namespace train_vocabulary_app {

struct TrainingDescriptors {
  std::vector<std::vector<Descriptor>> per_image;  ///< one entry per image read
  std::size_t total = 0;                           ///< descriptors in all images
  ImageProblemCounts skipped;                      ///< images refused, by reason
};

/// Reads `images` in order (each bag once, front to back) with the feature
/// options of `a`; refused images (bowg/features/image_check.h) are
/// skipped with a warning and counted. Shows the
/// first 20 % of the progress bar.
TrainingDescriptors extractDescriptors(const std::vector<ImageSource>& images, const Args& a);

}  // namespace train_vocabulary_app
}  // namespace bowg
