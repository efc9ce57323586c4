// Loading VINS' brief_pattern.yml layout; bad files name their path.
#include "bowg/features/brief_pattern.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "bowg/core/errors.h"
#include "core/special_files.h"

namespace bowg {
namespace {

std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string sequence(const char* key, int n, const std::string& value) {
  std::string s = std::string(key) + ":\n";
  for (int i = 0; i < n; ++i) s += "  - " + value + "\n";
  return s;
}

template <typename E>
void expectThrowNamingPath(const std::string& path) {
  try {
    loadBriefPattern(path);
    FAIL() << "no exception for " << path;
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(BriefPattern, LoadsTheSharedVinsPattern) {
  const std::string path = std::string(BOWG_SHARED_DATA_DIR) + "/vocabularies/brief_pattern.yml";
  if (!std::ifstream(path).good()) GTEST_SKIP() << "shared data absent: " << path;
  const std::vector<cv::Vec4i> p = loadBriefPattern(path);
  ASSERT_EQ(p.size(), 256u);
  // Read by hand from the file: x1[0] = 0, y1[0] = -10, x2[0] = 0, y2[0] = -6;
  // x1[2] = 11, y1[2] = 13, x2[2] = 13, y2[2] = 10.
  EXPECT_EQ(p[0], cv::Vec4i(0, -10, 0, -6));
  EXPECT_EQ(p[2], cv::Vec4i(11, 13, 13, 10));
}

TEST(BriefPattern, ReadsKeysByNameInAnyOrder) {
  const std::string path = writeFile(
      "pattern_ok.yml", "%YAML:1.0\n" + sequence("y2", 256, "4") + sequence("x1", 256, "1") +
                            sequence("y1", 256, "2") + sequence("x2", 256, "-3"));
  const std::vector<cv::Vec4i> p = loadBriefPattern(path);
  ASSERT_EQ(p.size(), 256u);
  EXPECT_EQ(p[255], cv::Vec4i(1, 2, -3, 4));
}

TEST(BriefPattern, FlowSequencesAreReadToo) {
  std::string text = "%YAML:1.0\n---\n";
  const char* keys[] = {"x1", "y1", "x2", "y2"};
  for (int k = 0; k < 4; ++k) {
    text += std::string(keys[k]) + ": [";
    for (int i = 0; i < 256; ++i) text += std::to_string(k == 0 ? i % 25 : -k) + (i < 255 ? ", " : "");
    text += "]\n";
  }
  const std::vector<cv::Vec4i> p = loadBriefPattern(writeFile("pattern_flow.yml", text));
  ASSERT_EQ(p.size(), 256u);
  EXPECT_EQ(p[30], cv::Vec4i(5, -1, -2, -3));
}

TEST(BriefPattern, MissingFileIsIoError) {
  expectThrowNamingPath<IoError>(std::string(BOWG_TEST_OUTPUT_DIR) + "/no_such_pattern.yml");
}

TEST(BriefPattern, CorruptFilesAreFormatErrors) {
  expectThrowNamingPath<FormatError>(writeFile("pattern_garbage.yml", "\x01\x02 not yaml [[[\n"));
  expectThrowNamingPath<FormatError>(writeFile(
      "pattern_short.yml", "%YAML:1.0\n" + sequence("x1", 255, "1") + sequence("y1", 256, "1") +
                               sequence("x2", 256, "1") + sequence("y2", 256, "1")));
  expectThrowNamingPath<FormatError>(writeFile(
      "pattern_missing_key.yml", "%YAML:1.0\n" + sequence("x1", 256, "1") +
                                     sequence("y1", 256, "1") + sequence("x2", 256, "1")));
  expectThrowNamingPath<FormatError>(writeFile(
      "pattern_real.yml", "%YAML:1.0\n" + sequence("x1", 256, "1.5") + sequence("y1", 256, "1") +
                              sequence("x2", 256, "1") + sequence("y2", 256, "1")));
  // Malformed YAML (an unterminated quote, a key without a sequence, a
  // second x1) and a flow sequence that is too long.
  expectThrowNamingPath<FormatError>(writeFile("pattern_quote.yml", "x1: [\"1, 2]\n"));
  expectThrowNamingPath<FormatError>(writeFile("pattern_nokey.yml", "x1:\ny1: [1]\n"));
  expectThrowNamingPath<FormatError>(
      writeFile("pattern_twice.yml", sequence("x1", 256, "1") + sequence("x1", 256, "1")));
  std::string long_flow = "x1: [";
  for (int i = 0; i < 300; ++i) long_flow += "1, ";
  expectThrowNamingPath<FormatError>(writeFile("pattern_long.yml", long_flow + "1]\n"));
  expectThrowNamingPath<FormatError>(writeFile(
      "pattern_huge.yml", "%YAML:1.0\n" + sequence("x1", 256, "1000") + sequence("y1", 256, "1") +
                              sequence("x2", 256, "1") + sequence("y2", 256, "1")));
}

TEST(BriefPattern, SpecialAndOversizedFilesAreRefusedFast) {
  const std::string dir = std::string(BOWG_TEST_OUTPUT_DIR) + "/pattern";
  const auto files = testing::makeSpecialFiles(dir, ".yml", 3ull << 30, "more than the limit");
  const auto load = [](const std::string& p) { loadBriefPattern(p); };
  testing::expectSpecialFilesRefused(files, load);
  testing::expectRefusedFast(dir + "/absent.yml", "No such file or directory", load);
  testing::makeSparseFile(dir + "/big_pattern.yml", 2u << 20);
  testing::expectRefusedFast(dir + "/big_pattern.yml", "larger than a pattern file can be", load);
}

}  // namespace
}  // namespace bowg
