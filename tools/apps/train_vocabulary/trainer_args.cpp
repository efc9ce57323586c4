// bowg_train_vocabulary's command line (trainer_args.h): the usage text, the
// integer parser that names the option, and one setter per option group.
#include "trainer_args.h"

#include <cstdint>
#include <exception>
#include <iostream>
#include <string>

#include "bowg/parameters/parameter_table.h"
#include "bowg/vocabulary/bow_vector.h"

namespace bowg {
namespace train_vocabulary_app {

const char* const kUsage =
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
    "  --k N                       branching factor, 2 to 1000 (default 10)\n"
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
    "  --gftt-max-corners N        --orb-max-features N\n"
    "  --config FILE               the features of a parameter file (a preset such as\n"
    "                              config/pipe_gftt.yaml: every feature key, gftt_levels\n"
    "                              too); not with the feature options above\n";

namespace {

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

// The command line being read: value() takes the argument after option
// `arg` as its value.
struct ArgReader {
  int argc;
  char** argv;
  int i;

  std::string value(const std::string& arg) {
    if (i + 1 >= argc) throw UsageError(arg + " needs a value");
    return argv[++i];
  }
};

/// --output, --format and the tree's options; false for any other.
bool setTreeOption(const std::string& arg, ArgReader* r, Args* a) {
  TrainingOptions& training = a->training;
  if (arg == "--output") {
    a->output = r->value(arg);
  } else if (arg == "--format") {
    a->format = r->value(arg);
  } else if (arg == "--k") {
    training.k = static_cast<int>(parseInteger(arg, r->value(arg), 2, kMaxBranching));
  } else if (arg == "--L") {
    training.L = static_cast<int>(parseInteger(arg, r->value(arg), 1, 64));
  } else if (arg == "--weighting") {
    training.weighting = weightingTypeFromString(r->value(arg));
  } else if (arg == "--scoring") {
    training.scoring = scoringTypeFromString(r->value(arg));
  } else if (arg == "--max-iterations") {
    training.max_iterations = static_cast<int>(parseInteger(arg, r->value(arg), 1, 1000000));
  } else if (arg == "--seed") {
    training.seed = static_cast<std::uint32_t>(parseInteger(arg, r->value(arg), 0, 0xffffffffl));
  } else if (arg == "--threads") {
    training.threads = static_cast<int>(parseInteger(arg, r->value(arg), 1, 64));
  } else {
    return false;
  }
  return true;
}

/// The bags, which of their images and how many features; false for any
/// other option.
bool setInputOption(const std::string& arg, ArgReader* r, Args* a) {
  if (arg == "--bag") {
    a->bags.push_back(r->value(arg));
  } else if (arg == "--image-topic") {
    a->image_topic = r->value(arg);
    if (a->image_topic.empty()) throw UsageError("--image-topic: empty topic name");
  } else if (arg == "--every") {
    a->every = parseInteger(arg, r->value(arg), 1, 1l << 40);
  } else if (arg == "--max-images") {
    a->max_images = parseInteger(arg, r->value(arg), 1, 1l << 40);
  } else if (arg == "--max-features-per-image") {
    a->max_features = parseInteger(arg, r->value(arg), 1, 1l << 40);
  } else {
    return false;
  }
  return true;
}

/// The feature extractor's options; false for any other.
bool setFeatureOption(const std::string& arg, ArgReader* r, Args* a) {
  FeatureOptions& features = a->features;
  if (arg == "--detector") {
    const std::string v = r->value(arg);
    if (v != "gftt" && v != "orb") throw UsageError("--detector: '" + v + "' is not gftt or orb");
    features.detector =
        v == "gftt" ? FeatureOptions::Detector::kGftt : FeatureOptions::Detector::kOrb;
  } else if (arg == "--descriptor") {
    const std::string v = r->value(arg);
    if (v != "orb" && v != "brief")
      throw UsageError("--descriptor: '" + v + "' is not orb or brief");
    features.descriptor =
        v == "orb" ? FeatureOptions::DescriptorType::kOrb : FeatureOptions::DescriptorType::kBrief;
  } else if (arg == "--brief-pattern") {
    features.brief_pattern_path = r->value(arg);
  } else if (arg == "--mask") {
    features.mask_path = r->value(arg);
  } else if (arg == "--upright") {
    features.compute_orientation = false;
  } else if (arg == "--gftt-max-corners") {
    features.gftt_max_corners = static_cast<int>(parseInteger(arg, r->value(arg), 1, 1000000));
  } else if (arg == "--orb-max-features") {
    features.orb_max_features = static_cast<int>(parseInteger(arg, r->value(arg), 1, 1000000));
  } else {
    return false;
  }
  return true;
}

}  // namespace

bool parseArgs(int argc, char** argv, Args* a) {
  ArgReader r{argc, argv, 1};
  std::string config, feature_option;
  for (; r.i < argc; ++r.i) {
    const std::string arg = argv[r.i];
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return false;
    }
    if (arg == "--config") {
      config = r.value(arg);
      continue;
    }
    if (setFeatureOption(arg, &r, a)) {
      feature_option = arg;
      continue;
    }
    if (setTreeOption(arg, &r, a) || setInputOption(arg, &r, a)) continue;
    if (!arg.empty() && arg[0] == '-') throw UsageError("unknown option '" + arg + "'");
    a->folders.push_back(arg);
  }
  if (a->output.empty()) throw UsageError("--output is required");
  if (a->folders.empty() && a->bags.empty()) throw UsageError("no image folder or --bag given");
  if (!config.empty()) {
    // One source for the features: a preset and flags on top of it would
    // leave the reader to guess which value won.
    if (!feature_option.empty()) {
      throw UsageError("--config " + config + " sets the features: " + feature_option +
                       " cannot be given with it");
    }
    a->features = loadParameterFile(config).features;
  }
  a->training.validate();
  a->features.validate();
  return true;
}

}  // namespace train_vocabulary_app
}  // namespace bowg
