// bowg_train_vocabulary: trains a vocabulary tree (paper Sec. III-A) from the
// images of folders and/or rosbags (sensor_msgs/Image or CompressedImage on
// one topic). Gathering the images and extracting their features live here;
// the training itself is the engine's bowg::trainVocabulary(). Bag images
// are read through the ROS layer (bag_images.h), as the nodelet reads them.
#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <iostream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include "bowg/core/errors.h"
#include "bowg/features/feature_extractor.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg/vocabulary/vocabulary_trainer.h"
#include "bowg_evaluation/image_file.h"
#include "bowg_ros/bag_images.h"

namespace {

const char* kUsage =
    "usage: bowg_train_vocabulary --output FILE [options] [FOLDER...] [--bag FILE...]\n"
    "\n"
    "Trains a k-ary vocabulary tree (hierarchical k-medians, k-means++ seeding) on the\n"
    "features of every .png/.jpg/.jpeg image found recursively in the folders (sorted by\n"
    "path) and of the image messages of the bags (in bag time order, after the folders).\n"
    "\n"
    "Output:\n"
    "  --output FILE               vocabulary to write (required)\n"
    "  --format FORMAT             bowg (default) | dbow2_yaml | dbow2_brief_yaml | dbow3 |\n"
    "                              dbow3_yaml | orbslam_txt | vins_bin\n"
    "Tree:\n"
    "  --k N                       branching factor, >= 2 (default 10)\n"
    "  --L N                       depth, >= 1 (default 6)\n"
    "  --weighting W               tf_idf (default) | tf | idf | binary\n"
    "  --scoring S                 l1 (default) | l2 | chi_square | kl | bhattacharyya | "
    "dot_product\n"
    "  --max-iterations N          k-medians iterations per clustering, >= 1 (default 10)\n"
    "  --seed N                    random seed (default 0); same input + seed = same vocabulary\n"
    "  --threads N                 worker threads, 1..64 (default 2)\n"
    "Input:\n"
    "  --bag FILE                  rosbag to read images from (repeatable)\n"
    "  --image-topic TOPIC         sensor_msgs/Image or sensor_msgs/CompressedImage topic of\n"
    "                              the bags (default /camera/image_raw)\n"
    "  --every N                   use every N-th image message of each bag (default 1)\n"
    "  --max-images N              use at most N images, evenly spaced over the sorted list\n"
    "  --max-features-per-image N  keep the N strongest features of each image\n"
    "Features (defaults: bowg::FeatureOptions):\n"
    "  --detector gftt|orb         --descriptor orb|brief\n"
    "  --brief-pattern FILE        BRIEF pattern (brief_pattern.yml layout), for --descriptor "
    "brief\n"
    "  --mask FILE                 8-bit mask image, non-zero = usable\n"
    "  --upright                   do not steer descriptors by orientation\n"
    "  --gftt-max-corners N        --orb-max-features N\n";

struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

long parseInteger(const std::string& option, const std::string& value, long lo, long hi) {
  std::size_t used = 0;
  long v = 0;
  try {
    v = std::stol(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size() || value.empty()) {
    throw UsageError(option + ": '" + value + "' is not an integer");
  }
  if (v < lo || v > hi) {
    throw UsageError(option + ": " + value + " is out of range [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
  }
  return v;
}

bool isImage(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* ext : {".png", ".jpg", ".jpeg"}) {
    const std::string e(ext);
    if (lower.size() > e.size() && lower.compare(lower.size() - e.size(), e.size(), e) == 0)
      return true;
  }
  return false;
}

void findImages(const std::string& dir, std::vector<std::string>* out, int depth = 0) {
  if (depth > 64) return;  // symlink loops
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr) throw bowg::IoError("cannot open folder '" + dir + "'");
  std::vector<std::string> entries;
  while (dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name != "." && name != "..") entries.push_back(name);
  }
  ::closedir(d);
  for (const std::string& name : entries) {
    const std::string path = dir + "/" + name;
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) continue;
    if (S_ISDIR(st.st_mode)) {
      findImages(path, out, depth + 1);
    } else if (S_ISREG(st.st_mode) && isImage(name)) {
      out->push_back(path);
    }
  }
}

// Redraws only when the percentage or the stage changes, so that a log file
// gets ~100 lines, not one per image.
void progressBar(double fraction, const std::string& stage) {
  static int last_percent = -1;
  static std::string last_stage;
  const int percent = static_cast<int>(fraction * 100 + 0.5);
  if (percent == last_percent && stage == last_stage) return;
  last_percent = percent;
  last_stage = stage;
  const int width = 40;
  const int filled = static_cast<int>(fraction * width + 0.5);
  std::string bar(static_cast<std::size_t>(filled), '=');
  bar.resize(width, ' ');
  std::fprintf(stderr, "\r[%s] %3d%% %-40s", bar.c_str(), percent, stage.c_str());
  if (fraction >= 1.0) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

// One training image: a file, or the index-th message on the image topic of
// bag number `bag` (indices count every message on the topic, before --every).
struct ImageSource {
  std::string path;
  int bag = -1;
  std::size_t index = 0;
};

rosbag::Bag openBag(const std::string& path) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw bowg::IoError("cannot open the bag '" + path + "': " + e.what());
  }
  return bag;
}

}  // namespace

int main(int argc, char** argv) {
  bowg::TrainingOptions training;
  bowg::FeatureOptions features;
  std::string output;
  std::string format = "bowg";
  long max_images = 0, max_features = 0;
  std::vector<std::string> folders, bags;
  std::string image_topic = "/camera/image_raw";
  long every = 1;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw UsageError(arg + " needs a value");
        return argv[++i];
      };
      if (arg == "-h" || arg == "--help") {
        std::cout << kUsage;
        return 0;
      } else if (arg == "--output") {
        output = value();
      } else if (arg == "--format") {
        format = value();
      } else if (arg == "--k") {
        training.k = static_cast<int>(parseInteger(arg, value(), 2, 4096));
      } else if (arg == "--L") {
        training.L = static_cast<int>(parseInteger(arg, value(), 1, 64));
      } else if (arg == "--weighting") {
        training.weighting = bowg::weightingTypeFromString(value());
      } else if (arg == "--scoring") {
        training.scoring = bowg::scoringTypeFromString(value());
      } else if (arg == "--max-iterations") {
        training.max_iterations = static_cast<int>(parseInteger(arg, value(), 1, 1000000));
      } else if (arg == "--seed") {
        training.seed = static_cast<std::uint32_t>(parseInteger(arg, value(), 0, 0xffffffffl));
      } else if (arg == "--threads") {
        training.threads = static_cast<int>(parseInteger(arg, value(), 1, 64));
      } else if (arg == "--bag") {
        bags.push_back(value());
      } else if (arg == "--image-topic") {
        image_topic = value();
        if (image_topic.empty()) throw UsageError("--image-topic: empty topic name");
      } else if (arg == "--every") {
        every = parseInteger(arg, value(), 1, 1l << 40);
      } else if (arg == "--max-images") {
        max_images = parseInteger(arg, value(), 1, 1l << 40);
      } else if (arg == "--max-features-per-image") {
        max_features = parseInteger(arg, value(), 1, 1l << 40);
      } else if (arg == "--detector") {
        const std::string v = value();
        if (v != "gftt" && v != "orb")
          throw UsageError("--detector: '" + v + "' is not gftt or orb");
        features.detector = v == "gftt" ? bowg::FeatureOptions::Detector::kGftt
                                        : bowg::FeatureOptions::Detector::kOrb;
      } else if (arg == "--descriptor") {
        const std::string v = value();
        if (v != "orb" && v != "brief")
          throw UsageError("--descriptor: '" + v + "' is not orb or brief");
        features.descriptor = v == "orb" ? bowg::FeatureOptions::DescriptorType::kOrb
                                         : bowg::FeatureOptions::DescriptorType::kBrief;
      } else if (arg == "--brief-pattern") {
        features.brief_pattern_path = value();
      } else if (arg == "--mask") {
        features.mask_path = value();
      } else if (arg == "--upright") {
        features.compute_orientation = false;
      } else if (arg == "--gftt-max-corners") {
        features.gftt_max_corners = static_cast<int>(parseInteger(arg, value(), 1, 1000000));
      } else if (arg == "--orb-max-features") {
        features.orb_max_features = static_cast<int>(parseInteger(arg, value(), 1, 1000000));
      } else if (!arg.empty() && arg[0] == '-') {
        throw UsageError("unknown option '" + arg + "'");
      } else {
        folders.push_back(arg);
      }
    }
    if (output.empty()) throw UsageError("--output is required");
    if (folders.empty() && bags.empty()) throw UsageError("no image folder or --bag given");
    training.validate();
    features.validate();
  } catch (const std::invalid_argument& e) {  // UsageError, InvalidParameter, bad enum names
    std::cerr << "error: " << e.what() << "\n\n" << kUsage;
    return 2;
  }

  try {
    const bowg::VocabularyFormat out_format = bowg::vocabularyFormatFromString(format);
    std::vector<std::string> files;
    for (const std::string& f : folders) findImages(f, &files);
    std::sort(files.begin(), files.end());
    std::vector<ImageSource> images;
    for (const std::string& f : files) images.push_back({f, -1, 0});
    for (std::size_t b = 0; b < bags.size(); ++b) {
      rosbag::Bag bag = openBag(bags[b]);
      rosbag::View view(bag, rosbag::TopicQuery(image_topic));
      if (view.size() == 0) {
        throw bowg::FormatError("the bag '" + bags[b] + "' has no message on " + image_topic +
                                " (see --image-topic)");
      }
      for (std::size_t i = 0; i < view.size(); i += static_cast<std::size_t>(every)) {
        images.push_back({"", static_cast<int>(b), i});
      }
    }
    if (images.empty()) {
      std::cerr << "error: no .png/.jpg/.jpeg image found in the given folders\n";
      return 1;
    }
    if (max_images > 0 && images.size() > static_cast<std::size_t>(max_images)) {
      std::vector<ImageSource> picked;
      for (long i = 0; i < max_images; ++i) {
        picked.push_back(images[static_cast<std::size_t>(i) * images.size() /
                                static_cast<std::size_t>(max_images)]);
      }
      images.swap(picked);
    }
    const bowg::FeatureExtractor extractor(features);
    std::vector<std::vector<bowg::Descriptor>> per_image;
    std::size_t total = 0, unreadable = 0;
    auto add = [&](const cv::Mat& image) {
      bowg::ImageFeatures f = extractor.extract(image);
      std::vector<std::size_t> order(f.size());
      for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
      if (max_features > 0 && order.size() > static_cast<std::size_t>(max_features)) {
        // Strongest first; ties by index keep it deterministic.
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
          return f.keypoints[a].response > f.keypoints[b].response;
        });
        order.resize(static_cast<std::size_t>(max_features));
        std::sort(order.begin(), order.end());
      }
      per_image.emplace_back();
      for (std::size_t j : order) per_image.back().push_back(f.descriptors[j]);
      total += per_image.back().size();
    };
    // Sources are ordered folders first, then bag by bag in message order:
    // each bag is read once, front to back.
    std::size_t i = 0;
    while (i < images.size()) {
      progressBar(0.2 * i / images.size(), "extracting features");
      if (images[i].bag < 0) {
        std::string why;
        const cv::Mat image = bowg::eval::readGreyImage(images[i].path, &why);
        if (image.empty()) {
          std::fprintf(stderr, "\nwarning: image '%s' skipped (%s)\n", images[i].path.c_str(),
                       why.c_str());
          ++unreadable;
        } else {
          add(image);
        }
        ++i;
        continue;
      }
      const int b = images[i].bag;
      rosbag::Bag bag = openBag(bags[b]);
      rosbag::View view(bag, rosbag::TopicQuery(image_topic));
      std::size_t index = 0;
      for (const rosbag::MessageInstance& m : view) {
        if (i >= images.size() || images[i].bag != b) break;
        if (index++ != images[i].index) continue;
        add(bowg_ros::readBagImage(m, bags[b]).grey);
        ++i;
        progressBar(0.2 * i / images.size(), "extracting features");
      }
      if (i < images.size() && images[i].bag == b) {
        throw bowg::FormatError("the bag '" + bags[b] + "' changed while it was read");
      }
    }
    std::fprintf(stderr, "\n%zu images (%zu unreadable), %zu descriptors\n", per_image.size(),
                 unreadable, total);
    const bowg::Vocabulary v = bowg::trainVocabulary(
        per_image, training,
        [](double f, const std::string& stage) { progressBar(0.2 + 0.8 * f, stage); });
    bowg::saveVocabulary(v, output, out_format);
    std::fprintf(stderr, "wrote %s: k=%d L=%d nodes=%zu words=%zu fingerprint %016llx\n",
                 output.c_str(), v.branching(), v.depth(), v.nodeCount(), v.wordCount(),
                 static_cast<unsigned long long>(v.fingerprint()));
  } catch (const std::exception& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
