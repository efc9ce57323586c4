// The feature extraction of bowg_train_vocabulary (descriptor_extraction.h):
// the strongest-first selection and the reading of files and bag runs.
#include "descriptor_extraction.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "bowg/core/errors.h"
#include "bowg/features/feature_extractor.h"
#include "bowg/features/image_decoding.h"
#include "bowg_bag_reading/bag_images.h"
#include "progress_bar.h"

namespace bowg {
namespace train_vocabulary_app {
namespace {

// Adds the descriptors of one image at a time.
class DescriptorCollector {
 public:
  DescriptorCollector(const FeatureOptions& features, long max_features)
      : extractor_(features), max_features_(max_features) {}

  const FeatureOptions& features() const { return extractor_.options(); }

  /// The image of `source` (named in the warning), or its refusal.
  void add(const cv::Mat& image, const ImageCheck& check, const std::string& source) {
    if (!check.ok()) {
      std::fprintf(stderr, "\nwarning: image %s skipped (%s)\n", source.c_str(),
                   check.message().c_str());
      result_.skipped.add(check.problem);
      return;
    }
    ImageFeatures f = extractor_.extract(image);
    std::vector<std::size_t> order(f.size());
    for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
    if (max_features_ > 0 && order.size() > static_cast<std::size_t>(max_features_)) {
      // Strongest first; ties by index keep it deterministic.
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return f.keypoints[a].response > f.keypoints[b].response;
      });
      order.resize(static_cast<std::size_t>(max_features_));
      std::sort(order.begin(), order.end());
    }
    result_.per_image.emplace_back();
    for (std::size_t j : order) result_.per_image.back().push_back(f.descriptors[j]);
    result_.total += result_.per_image.back().size();
  }

  TrainingDescriptors& result() { return result_; }

 private:
  const FeatureExtractor extractor_;
  const long max_features_;
  TrainingDescriptors result_;
};

void addFile(const std::string& path, DescriptorCollector* collector) {
  ImageCheck check;
  const cv::Mat image = readGreyImageFile(path, collector->features(), &check);
  collector->add(image, check, "'" + path + "'");
}

/// The run of sources from images[*i] on that are messages of the same bag,
/// read in one pass; *i ends after the run.
void addBagRun(const std::vector<ImageSource>& images, std::size_t* i, const Args& a,
               DescriptorCollector* collector) {
  const int b = images[*i].bag;
  rosbag::Bag bag = openBag(a.bags[b]);
  rosbag::View view(bag, rosbag::TopicQuery(a.image_topic));
  std::size_t index = 0;
  for (const rosbag::MessageInstance& m : view) {
    if (*i >= images.size() || images[*i].bag != b) break;
    if (index++ != images[*i].index) continue;
    const bowg::bag::BagImage image = bowg::bag::readBagImage(m, a.bags[b], collector->features());
    collector->add(image.grey, image.check, "#" + std::to_string(index - 1) + " of " + a.bags[b]);
    ++*i;
    progressBar(0.2 * *i / images.size(), "extracting features");
  }
  if (*i < images.size() && images[*i].bag == b) {
    throw FormatError("the bag '" + a.bags[b] + "' changed while it was read");
  }
}

}  // namespace

TrainingDescriptors extractDescriptors(const std::vector<ImageSource>& images, const Args& a) {
  DescriptorCollector collector(a.features, a.max_features);
  // Sources are ordered folders first, then bag by bag in message order:
  // each bag is read once, front to back.
  std::size_t i = 0;
  while (i < images.size()) {
    progressBar(0.2 * i / images.size(), "extracting features");
    if (images[i].bag < 0) {
      addFile(images[i].path, &collector);
      ++i;
    } else {
      addBagRun(images, &i, a, &collector);
    }
  }
  return std::move(collector.result());
}

}  // namespace train_vocabulary_app
}  // namespace bowg
