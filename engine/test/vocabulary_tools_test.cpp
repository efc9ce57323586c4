// End-to-end tests of the command-line tools bowg_train_vocabulary and
// bowg_convert_vocabulary: exit codes, determinism, and that what they write
// loads back as the vocabulary asked for.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bowg/vocabulary.h"
#include "bowg/vocabulary_io.h"
#include "feature_test_images.h"

namespace bowg {
namespace {

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/vocabulary_tools_test";

// Runs a shell command and returns its exit code (-1 if it did not exit).
int run(const std::string& command) {
  const int status = std::system((command + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

class VocabularyTools : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_EQ(run("rm -rf " + kDir + " && mkdir -p " + kDir + "/images/sub"), 0);
    // Six textured images, two in a subfolder (the trainer recurses).
    for (int i = 0; i < 6; ++i) {
      const std::string folder = kDir + (i < 4 ? "/images/" : "/images/sub/");
      cv::imwrite(folder + "img" + std::to_string(i) + ".png",
                  test::texturedImage(320, 240, 200, 100 + i));
    }
  }

  static std::string train(const std::string& out, const std::string& extra = "") {
    return std::string(BOWG_TRAIN_VOCABULARY_BIN) + " --output " + out +
           " --k 4 --L 3 --seed 7 --threads 1 " + extra + " " + kDir + "/images";
  }
};

TEST_F(VocabularyTools, TrainWritesTheRequestedTreeDeterministically) {
  const std::string a = kDir + "/a.bowgvoc", b = kDir + "/b.bowgvoc";
  ASSERT_EQ(run(train(a)), 0);
  ASSERT_EQ(run(train(b)), 0);
  const Vocabulary voc = loadVocabulary(a);
  EXPECT_EQ(voc.branching(), 4);
  EXPECT_EQ(voc.depth(), 3);
  EXPECT_GT(voc.wordCount(), 16u);   // more than two full levels
  EXPECT_LE(voc.wordCount(), 64u);   // at most k^L
  EXPECT_EQ(readAll(a), readAll(b)) << "same images + seed must give the same file";
}

TEST_F(VocabularyTools, ConvertRoundTripKeepsTheVocabulary) {
  const std::string src = kDir + "/src.bowgvoc";
  ASSERT_EQ(run(train(src)), 0);
  const std::string yml = kDir + "/conv.yml.gz", back = kDir + "/back.bowgvoc";
  ASSERT_EQ(run(std::string(BOWG_CONVERT_VOCABULARY_BIN) + " " + src + " " + yml), 0);
  ASSERT_EQ(run(std::string(BOWG_CONVERT_VOCABULARY_BIN) + " " + yml + " " + back), 0);
  EXPECT_EQ(loadVocabulary(src).fingerprint(), loadVocabulary(back).fingerprint());
}

TEST_F(VocabularyTools, BadArgumentsAndMissingInputsFailWithDistinctCodes) {
  // Usage errors exit 2, I/O and format errors exit 1; nothing is written.
  EXPECT_EQ(run(std::string(BOWG_TRAIN_VOCABULARY_BIN) + " --k 1 --output " + kDir +
                "/x.bowgvoc " + kDir + "/images"), 2);
  EXPECT_EQ(run(std::string(BOWG_TRAIN_VOCABULARY_BIN) + " " + kDir + "/images"), 2);
  EXPECT_EQ(run(std::string(BOWG_CONVERT_VOCABULARY_BIN) + " " + kDir + "/missing.bowgvoc " +
                kDir + "/y.bowgvoc"), 1);
  std::ofstream(kDir + "/garbage.bowgvoc") << "not a vocabulary";
  EXPECT_EQ(run(std::string(BOWG_CONVERT_VOCABULARY_BIN) + " " + kDir + "/garbage.bowgvoc " +
                kDir + "/z.bowgvoc"), 1);
  EXPECT_NE(run("test -e " + kDir + "/x.bowgvoc"), 0);
  EXPECT_NE(run("test -e " + kDir + "/z.bowgvoc"), 0);
}

}  // namespace
}  // namespace bowg
