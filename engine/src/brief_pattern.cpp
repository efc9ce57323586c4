#include "bowg/brief_pattern.h"

#include <cstdlib>
#include <fstream>

#include "bowg/errors.h"

namespace bowg {
namespace {

std::vector<int> readSequence(const cv::FileStorage& fs, const char* key, const std::string& path) {
  const cv::FileNode node = fs[key];
  if (node.empty() || !node.isSeq()) {
    throw FormatError("BRIEF pattern file " + path + ": missing integer sequence '" + key + "'");
  }
  if (static_cast<int>(node.size()) != kBriefPatternPairs) {
    throw FormatError("BRIEF pattern file " + path + ": sequence '" + key + "' has " +
                      std::to_string(node.size()) + " entries, expected " +
                      std::to_string(kBriefPatternPairs));
  }
  std::vector<int> values;
  values.reserve(kBriefPatternPairs);
  for (const cv::FileNode& item : node) {
    if (!item.isInt()) {
      throw FormatError("BRIEF pattern file " + path + ": sequence '" + key +
                        "' holds a non-integer entry");
    }
    const int v = static_cast<int>(item);
    if (std::abs(v) > kBriefPatternMaxOffset) {
      throw FormatError("BRIEF pattern file " + path + ": sequence '" + key + "' entry " +
                        std::to_string(v) + " exceeds +-" + std::to_string(kBriefPatternMaxOffset) +
                        " px");
    }
    values.push_back(v);
  }
  return values;
}

}  // namespace

std::vector<cv::Vec4i> loadBriefPattern(const std::string& path) {
  // FileStorage does not tell a missing file from a corrupt one: check first.
  if (!std::ifstream(path).good()) {
    throw IoError("cannot open BRIEF pattern file " + path);
  }
  cv::FileStorage fs;
  try {
    if (!fs.open(path, cv::FileStorage::READ)) {
      throw FormatError("BRIEF pattern file " + path + " is not an OpenCV YAML/XML file");
    }
    const std::vector<int> x1 = readSequence(fs, "x1", path);
    const std::vector<int> y1 = readSequence(fs, "y1", path);
    const std::vector<int> x2 = readSequence(fs, "x2", path);
    const std::vector<int> y2 = readSequence(fs, "y2", path);
    std::vector<cv::Vec4i> pattern(kBriefPatternPairs);
    for (int i = 0; i < kBriefPatternPairs; ++i) pattern[i] = cv::Vec4i(x1[i], y1[i], x2[i], y2[i]);
    return pattern;
  } catch (const cv::Exception& e) {
    throw FormatError("BRIEF pattern file " + path + " could not be parsed: " + e.what());
  }
}

}  // namespace bowg
