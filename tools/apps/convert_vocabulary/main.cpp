// bowg_convert_vocabulary: converts a vocabulary between our .bowgvoc and the
// formats of DBoW2, DBoW3, ORB-SLAM and VINS (see bowg/vocabulary/vocabulary_io.h).
#include <cstdio>
#include <iostream>
#include <string>

#include "bowg/core/errors.h"
#include "bowg/vocabulary/vocabulary_io.h"

namespace {

const char* kUsage =
    "usage: bowg_convert_vocabulary <input> <output> [--format FORMAT] [--scoring SCORING]\n"
    "\n"
    "Converts a vocabulary tree. The input format is detected from the file's content.\n"
    "The output format is FORMAT, or else chosen from the output's extension:\n"
    "  .bowgvoc -> bowg, .yml/.yml.gz/.yaml -> dbow2_yaml, .dbow3 -> dbow3,\n"
    "  .txt -> orbslam_txt, .bin -> vins_bin.\n"
    "FORMAT: bowg | dbow2_yaml | dbow2_brief_yaml | dbow3 | dbow3_yaml | orbslam_txt | vins_bin\n"
    "SCORING (replaces the stored default): l1 | l2 | chi_square | kl | bhattacharyya | "
    "dot_product\n";

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bowg::VocabularyFormat formatFromExtension(const std::string& path) {
  using F = bowg::VocabularyFormat;
  if (endsWith(path, ".bowgvoc")) return F::kBowg;
  if (endsWith(path, ".yml") || endsWith(path, ".yml.gz") || endsWith(path, ".yaml") ||
      endsWith(path, ".yaml.gz")) {
    return F::kDbow2Yaml;
  }
  if (endsWith(path, ".dbow3")) return F::kDbow3Binary;
  if (endsWith(path, ".txt")) return F::kOrbSlamText;
  if (endsWith(path, ".bin")) return F::kVinsBinary;
  throw std::invalid_argument("cannot tell the output format from the name '" + path +
                              "': pass --format");
}

}  // namespace

int main(int argc, char** argv) {
  std::string input, output, format, scoring;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    }
    if (arg == "--format" || arg == "--scoring") {
      if (i + 1 >= argc) {
        std::cerr << "error: " << arg << " needs a value\n" << kUsage;
        return 2;
      }
      (arg == "--format" ? format : scoring) = argv[++i];
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "error: unknown option '" << arg << "'\n" << kUsage;
      return 2;
    } else if (input.empty()) {
      input = arg;
    } else if (output.empty()) {
      output = arg;
    } else {
      std::cerr << "error: unexpected argument '" << arg << "'\n" << kUsage;
      return 2;
    }
  }
  if (input.empty() || output.empty()) {
    std::cerr << "error: need an input and an output path\n" << kUsage;
    return 2;
  }
  try {
    const bowg::VocabularyFormat out_format =
        format.empty() ? formatFromExtension(output) : bowg::vocabularyFormatFromString(format);
    const bowg::ScoringType new_scoring =
        scoring.empty() ? bowg::ScoringType::kL1 : bowg::scoringTypeFromString(scoring);
    const bowg::VocabularyFormat in_format = bowg::detectVocabularyFormat(input);
    bowg::Vocabulary v = bowg::loadVocabulary(input, in_format);
    if (!scoring.empty()) v.setScoring(new_scoring);
    std::cerr << "read " << input << " (" << bowg::toString(in_format) << "): k=" << v.branching()
              << " L=" << v.depth() << " nodes=" << v.nodeCount() << " words=" << v.wordCount()
              << " weighting=" << bowg::toString(v.weighting())
              << " scoring=" << bowg::toString(v.scoring()) << "\n";
    bowg::saveVocabulary(v, output, out_format);
    char fp[32];
    std::snprintf(fp, sizeof(fp), "%016llx", static_cast<unsigned long long>(v.fingerprint()));
    std::cerr << "wrote " << output << " (" << bowg::toString(out_format) << "), fingerprint " << fp
              << "\n";
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
