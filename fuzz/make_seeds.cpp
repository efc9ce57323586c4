// Writes the seed corpora of the fuzz targets (scripts/fuzz.sh): valid files
// of every format the loaders read, made by the project's own writers, so
// the fuzzer starts from inputs that reach deep into each loader.
//   bowg_fuzz_seeds <corpus folder>
// creates <folder>/<target>/ for vocabulary, database, brief_pattern, config,
// ground_truth, image (every image format read) and features_message.
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "encoded_test_images.h"
#include "feature_bytes.h"
#include "seed_world.h"

namespace {

void makeDir(const std::string& d) {
  if (::mkdir(d.c_str(), 0755) != 0 && errno != EEXIST) {
    throw bowg::IoError("cannot create " + d);
  }
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeAll(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
  if (!out) throw bowg::IoError("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bowg_fuzz_seeds <corpus folder>\n");
    return 2;
  }
  const std::string root = argv[1];
  try {
    makeDir(root);
    for (const char* t : {"vocabulary", "database", "brief_pattern", "config", "ground_truth",
                          "image", "features_message"}) {
      makeDir(root + "/" + t);
    }
    // Vocabularies: a small tree in every format; the first byte of a
    // vocabulary input selects the loader (0 = detection, 1 + format).
    const bowg::Vocabulary small = bowg::testing::makeSyntheticVocabulary(3, 2, 7);
    const char* names[] = {"bowg", "dbow2.yml", "brief.yml", "dbow3.yml", "dbow3.bin", "orbslam.txt",
                           "vins.bin"};
    for (int f = 0; f < 7; ++f) {
      const std::string file = root + "/vocabulary/tmp_" + names[f];
      bowg::saveVocabulary(small, file, static_cast<bowg::VocabularyFormat>(f));
      const std::string body = readAll(file);
      std::remove(file.c_str());
      writeAll(root + "/vocabulary/detect_" + names[f], std::string(1, '\0') + body);
      writeAll(root + "/vocabulary/format_" + names[f], std::string(1, static_cast<char>(1 + f)) + body);
    }
    // Databases: after the forward pass, and mid-revisit (chains, hypotheses).
    bowg::LoopDetector detector(bowg::fuzz::seedVocabulary(), bowg::fuzz::seedOptions());
    for (int i = 0; i < 28; ++i) {
      detector.process(bowg::fuzz::seedKeyframe(i));
      if (i == 14 || i == 27) detector.save(root + "/database/after_" + std::to_string(i) + ".bowgdb");
    }
    // BRIEF pattern: block and flow sequences.
    std::string block = "%YAML:1.0\n", flow = "%YAML:1.0\n";
    for (const char* key : {"x1", "y1", "x2", "y2"}) {
      block += std::string(key) + ":\n";
      flow += std::string(key) + ": [";
      for (int i = 0; i < 256; ++i) {
        block += "  - " + std::to_string(i % 25 - 12) + "\n";
        flow += std::to_string(i % 17 - 8) + (i < 255 ? ", " : "]\n");
      }
    }
    writeAll(root + "/brief_pattern/block.yml", block);
    writeAll(root + "/brief_pattern/flow.yml", flow);
    // Configuration: a flat file touching every kind of row.
    writeAll(root + "/config/pipe.yaml",
             "# preset\nfeature_detector: orb\nscoring: l1\nword_groups: true\nlambda_1: 0.7\n"
             "min_score: 1.2\nrecent_exclusion: 75\ntemporal_k: 3\nmin_inliers: 40\n"
             "descriptor: 'orb'\nnormaliser_distance_m: \"0.03\"\n");
    // Ground truth.
    writeAll(root + "/ground_truth/gt.txt",
             "# query: matches\n217: 0,1,2,3\n218: 0,1,2\n# comment\n300: 12\n");
    // Images: every format read, grey and colour, and a JPEG cut short.
    const cv::Mat grey = bowg::test::noiseImage(64, 48);
    cv::Mat colour;
    cv::merge(std::vector<cv::Mat>{grey, grey, grey}, colour);
    for (const char* ext : {".png", ".jpg", ".bmp", ".pgm"}) {
      const std::vector<std::uint8_t> bytes = bowg::test::encodeImage(grey, ext);
      writeAll(root + "/image/grey" + ext, std::string(bytes.begin(), bytes.end()));
    }
    for (const char* ext : {".png", ".jpg", ".ppm"}) {
      const std::vector<std::uint8_t> bytes = bowg::test::encodeImage(colour, ext);
      writeAll(root + "/image/colour" + ext, std::string(bytes.begin(), bytes.end()));
    }
    const std::vector<std::uint8_t> cut = bowg::test::truncatedJpeg();
    writeAll(root + "/image/truncated.jpg", std::string(cut.begin(), cut.end()));
    // Upstream features: keyframes of the seed corridor.
    for (int i : {0, 10}) {
      writeAll(root + "/features_message/keyframe_" + std::to_string(i),
               bowg::fuzz::featureBytes(bowg::fuzz::seedKeyframe(i).features));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bowg_fuzz_seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}
