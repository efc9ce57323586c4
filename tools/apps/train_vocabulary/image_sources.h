// The training images of bowg_train_vocabulary, before any is read: the
// image files found in the folders (sorted by path), then the chosen
// messages of each bag, thinned to --max-images.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <rosbag/bag.h>

#include "trainer_args.h"

namespace bowg {
namespace train_vocabulary_app {

// One training image: a file, or the index-th message on the image topic of
// bag number `bag` (indices count every message on the topic, before --every).
struct ImageSource {
  std::string path;
  int bag = -1;
  std::size_t index = 0;
};

/// Opens a bag for reading; throws bowg::IoError naming it.
rosbag::Bag openBag(const std::string& path);

/// The files of a.folders, then every a.every-th message on a.image_topic of
/// each of a.bags. Throws when a folder or bag cannot be read or a bag has no
/// message on the topic.
std::vector<ImageSource> gatherImageSources(const Args& a);

/// At most `max_images` of `images`, evenly spaced (all of them for 0).
std::vector<ImageSource> pickEvenly(std::vector<ImageSource> images, long max_images);

}  // namespace train_vocabulary_app
}  // namespace bowg
