// The features bowg_train_vocabulary trains on: every image source read
// (files as grey images, bag messages through the ROS layer, bag_images.h,
// as the nodelet reads them) and its descriptors extracted, the strongest
// --max-features-per-image of them kept.
#pragma once

#include <cstddef>
#include <vector>

#include "bowg/core/types.h"
#include "image_sources.h"
#include "trainer_args.h"

namespace bowg {
namespace train_vocabulary_app {

struct TrainingDescriptors {
  std::vector<std::vector<Descriptor>> per_image;  ///< one entry per image read
  std::size_t total = 0;                           ///< descriptors in all images
  std::size_t unreadable = 0;                      ///< image files skipped
};

/// Reads `images` in order (each bag once, front to back) with the feature
/// options of `a`; unreadable files are skipped with a warning. Shows the
/// first 20 % of the progress bar.
TrainingDescriptors extractDescriptors(const std::vector<ImageSource>& images, const Args& a);

}  // namespace train_vocabulary_app
}  // namespace bowg
