// End-to-end tests of the command-line tools bowg_train_vocabulary and
// bowg_convert_vocabulary: exit codes, determinism, that what they write
// loads back as the vocabulary asked for, and that the trainer reads rosbags
// (--bag, --image-topic, --every) exactly as it reads image folders.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <rosbag/bag.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/String.h>

#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "encoded_test_images.h"
#include "feature_test_images.h"
#include "shell_command.h"

namespace bowg {
namespace {

const std::string kDir = std::string(BOWG_TEST_OUTPUT_DIR) + "/vocabulary_tools_test";

using tool_test::readAll;
using tool_test::run;

class VocabularyTools : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_EQ(run("rm -rf " + kDir + " && mkdir -p " + kDir + "/images/sub " + kDir + "/even"),
              0);
    // Six textured images, two in a subfolder (the trainer recurses). Sorted
    // by path they are img0 .. img5 ("images/img3" < "images/sub/img4").
    // "even" holds img0, img2, img4: what --every 2 must pick from the bag.
    // The bag holds the same six as mono8 messages in the same order, with
    // chatter on another topic that --image-topic must leave out.
    rosbag::Bag bag(kDir + "/images.bag", rosbag::bagmode::Write);
    for (int i = 0; i < 6; ++i) {
      const cv::Mat image = test::texturedImage(320, 240, 200, 100 + i);
      const std::string name = "img" + std::to_string(i) + ".png";
      cv::imwrite(kDir + (i < 4 ? "/images/" : "/images/sub/") + name, image);
      if (i % 2 == 0) cv::imwrite(kDir + "/even/" + name, image);
      const ros::Time stamp(10 + i, 0);
      sensor_msgs::Image msg;
      msg.header.stamp = stamp;
      msg.height = static_cast<std::uint32_t>(image.rows);
      msg.width = static_cast<std::uint32_t>(image.cols);
      msg.encoding = "mono8";
      msg.step = msg.width;
      msg.data.assign(image.datastart, image.dataend);
      bag.write("/camera/image_raw", stamp, msg);
      std_msgs::String chatter;
      chatter.data = "not an image";
      bag.write("/chatter", stamp, chatter);
      // The same image as PNG on a CompressedImage topic.
      sensor_msgs::CompressedImage compressed;
      compressed.header.stamp = stamp;
      compressed.format = "mono8; png compressed";
      cv::imencode(".png", image, compressed.data);
      bag.write("/camera/image_raw/compressed", stamp, compressed);
    }
    bag.close();
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

TEST_F(VocabularyTools, ConfigTrainsOnAParameterFilesFeatures) {
  std::ofstream(kDir + "/orb50.yaml") << "feature_detector: orb\norb_max_features: 50\n"
                                      << "min_score: 0.9\n";  // a detector key: not read here
  std::ofstream(kDir + "/levels.yaml") << "gftt_levels: 3\n";
  const std::string flags = kDir + "/flags.bowgvoc", config = kDir + "/config.bowgvoc";
  ASSERT_EQ(run(train(flags, "--detector orb --orb-max-features 50")), 0);
  ASSERT_EQ(run(train(config, "--config " + kDir + "/orb50.yaml")), 0);
  EXPECT_EQ(readAll(flags), readAll(config));
  // A key the trainer has no flag for reaches the extractor: corners on
  // three pyramid levels give another tree than the single level.
  const std::string single = kDir + "/single.bowgvoc", levels = kDir + "/levels.bowgvoc";
  ASSERT_EQ(run(train(single)), 0);
  ASSERT_EQ(run(train(levels, "--config " + kDir + "/levels.yaml")), 0);
  EXPECT_NE(readAll(single), readAll(levels));
  // The features come from one place; a bad file is named; nothing is written.
  const std::string out = kDir + "/refused.bowgvoc", err = kDir + "/config_err.txt";
  EXPECT_EQ(run(train(out, "--config " + kDir + "/orb50.yaml --upright"), err), 2);
  EXPECT_NE(readAll(err).find("--upright cannot be given with it"), std::string::npos);
  std::ofstream(kDir + "/typo.yaml") << "gftt_levls: 3\n";
  EXPECT_NE(run(train(out, "--config " + kDir + "/typo.yaml"), err), 0);
  EXPECT_NE(readAll(err).find("typo.yaml"), std::string::npos) << readAll(err);
  EXPECT_EQ(run(train(out, "--config " + kDir + "/missing.yaml"), err), 1);  // I/O, not usage
  EXPECT_NE(readAll(err).find("missing.yaml"), std::string::npos) << readAll(err);
  EXPECT_NE(run("test -e " + out), 0);
}

TEST_F(VocabularyTools, TrainingFromABagEqualsTrainingFromTheSameImagesInAFolder) {
  // trainVocabulary is deterministic in (descriptors in order, seed): the bag's
  // six messages are the folder's six images in the same order, so the two
  // vocabularies must be the same tree, word for word.
  const std::string folder = kDir + "/folder.bowgvoc", bag = kDir + "/bag.bowgvoc";
  ASSERT_EQ(run(train(folder)), 0);
  ASSERT_EQ(run(std::string(BOWG_TRAIN_VOCABULARY_BIN) + " --output " + bag +
                " --k 4 --L 3 --seed 7 --threads 1 --bag " + kDir + "/images.bag"),
            0);
  EXPECT_EQ(loadVocabulary(folder).fingerprint(), loadVocabulary(bag).fingerprint());

  // Compressed messages decode to the same (lossless PNG) images.
  const std::string compressed = kDir + "/compressed.bowgvoc";
  ASSERT_EQ(run(std::string(BOWG_TRAIN_VOCABULARY_BIN) + " --output " + compressed +
                " --k 4 --L 3 --seed 7 --threads 1 --image-topic /camera/image_raw/compressed"
                " --bag " + kDir + "/images.bag"),
            0);
  EXPECT_EQ(loadVocabulary(folder).fingerprint(), loadVocabulary(compressed).fingerprint());
}

TEST_F(VocabularyTools, EveryNthBagMessageAndFoldersPlusBagsCombine) {
  // --every 2 keeps messages 0, 2, 4 = the "even" folder.
  const std::string even_folder = kDir + "/even_folder.bowgvoc",
                    even_bag = kDir + "/even_bag.bowgvoc";
  ASSERT_EQ(run(std::string(BOWG_TRAIN_VOCABULARY_BIN) + " --output " + even_folder +
                " --k 4 --L 3 --seed 7 --threads 1 " + kDir + "/even"),
            0);
  ASSERT_EQ(run(std::string(BOWG_TRAIN_VOCABULARY_BIN) + " --output " + even_bag +
                " --k 4 --L 3 --seed 7 --threads 1 --every 2 --bag " + kDir + "/images.bag"),
            0);
  EXPECT_EQ(loadVocabulary(even_folder).fingerprint(), loadVocabulary(even_bag).fingerprint());
  // Folder + bag: nine images, a different training set, hence (almost
  // surely) a different tree than the six of the folder alone.
  const std::string both = kDir + "/both.bowgvoc", folder = kDir + "/folder_only.bowgvoc";
  ASSERT_EQ(run(train(both, "--every 2 --bag " + kDir + "/images.bag")), 0);
  ASSERT_EQ(run(train(folder)), 0);
  EXPECT_NE(loadVocabulary(both).fingerprint(), loadVocabulary(folder).fingerprint());
}

// Bad CompressedImage messages (empty, a JPEG cut short, a PNG declaring
// 30000 x 30000 pixels) are skipped and counted by reason, as in a folder;
// the training goes on with the good ones.
TEST_F(VocabularyTools, BadBagImagesAreSkippedAndCountedByReason) {
  const std::string bag_path = kDir + "/damaged.bag";
  {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Write);
    for (int i = 0; i < 9; ++i) {
      sensor_msgs::CompressedImage msg;
      msg.header.stamp = ros::Time(10 + i, 0);
      msg.format = "mono8; png compressed";
      if (i < 6) cv::imencode(".png", test::texturedImage(320, 240, 200, 100 + i), msg.data);
      if (i == 7) msg.data = test::truncatedJpeg();
      if (i == 8) msg.data = test::pngDeclaring(30000, 30000);
      bag.write("/camera/image_raw/compressed", msg.header.stamp, msg);
    }
  }
  const std::string out = kDir + "/damaged.bowgvoc";
  const std::string log = kDir + "/damaged.log";
  ASSERT_EQ(run(std::string(BOWG_TRAIN_VOCABULARY_BIN) + " --output " + out +
                    " --k 4 --L 3 --seed 7 --threads 1 --image-topic /camera/image_raw/compressed"
                    " --bag " + bag_path,
                log),
            0)
      << readAll(log);
  const std::string text = readAll(log);
  for (const char* expected :
       {"#6 of ", "skipped (empty: ", "#7 of ", "skipped (truncated: ", "#8 of ",
        "skipped (too_large: ", "PNG 30000 x 30000 = 900000000 pixels",
        "6 images (3 skipped: 1 empty, 1 truncated, 1 too_large)"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
  }
}

TEST_F(VocabularyTools, BadBagInputsFailClearly) {
  const std::string out = kDir + "/bad.bowgvoc";
  const std::string base =
      std::string(BOWG_TRAIN_VOCABULARY_BIN) + " --output " + out + " --k 4 --L 3 ";
  // Usage errors: exit 2.
  EXPECT_EQ(run(base + "--every 0 --bag " + kDir + "/images.bag"), 2);
  EXPECT_EQ(run(base + "--bag"), 2);
  // Missing bag, topic without messages, topic of the wrong type: exit 1.
  EXPECT_EQ(run(base + "--bag " + kDir + "/missing.bag"), 1);
  EXPECT_EQ(run(base + "--image-topic /nothing --bag " + kDir + "/images.bag"), 1);
  EXPECT_EQ(run(base + "--image-topic /chatter --bag " + kDir + "/images.bag"), 1);
  EXPECT_NE(run("test -e " + out), 0) << "a failed run must not write the vocabulary";
}

}  // namespace
}  // namespace bowg
