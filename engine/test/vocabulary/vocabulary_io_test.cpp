// Vocabulary files: round trips through every format (same fingerprint),
// format detection, bit orders of the foreign formats, clear errors. Bad
// input: vocabulary_io_bad_input_test.cpp.
#include "bowg/vocabulary/vocabulary_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "synthetic_vocabulary.h"
#include "vocabulary/vocabulary_files.h"

namespace bowg {
namespace {

using testing::FormatCase;
using testing::kCases;
using testing::outPath;
using testing::readAll;
using testing::unbalanced;
using testing::writeAll;

TEST(VocabularyIo, FormatNames) {
  for (const auto& c : kCases) EXPECT_EQ(vocabularyFormatFromString(toString(c.format)), c.format);
  EXPECT_THROW(vocabularyFormatFromString("dbow4"), std::invalid_argument);
}

TEST(VocabularyIo, EveryFormatRoundTripsWithTheSameFingerprint) {
  for (const Vocabulary& v : {testing::makeSyntheticVocabulary(4, 3, 5), unbalanced()}) {
    for (const auto& c : kCases) {
      SCOPED_TRACE(c.file);
      const std::string path = outPath(c.file);
      saveVocabulary(v, path, c.format);
      const Vocabulary back = loadVocabulary(path);
      EXPECT_EQ(back.fingerprint(), v.fingerprint());
      EXPECT_EQ(back.scoring(), v.scoring());
      EXPECT_EQ(back.weighting(), v.weighting());
      EXPECT_EQ(back.wordCount(), v.wordCount());
      EXPECT_EQ(back.nodeCount(), v.nodeCount());
      // Every loader's word weights are the leaves' (the .bowgvoc loader
      // builds its word table while it streams the tree).
      for (WordId w = 0; w < back.wordCount(); ++w) {
        ASSERT_EQ(back.wordWeight(w), back.nodes()[back.nodeOfWord(w)].weight) << "word " << w;
        ASSERT_EQ(back.wordWeight(w), v.wordWeight(w)) << "word " << w;
      }
    }
  }
}

TEST(VocabularyIo, DetectsFormatsFromContent) {
  const Vocabulary v = testing::makeSyntheticVocabulary(3, 2, 2);
  for (const auto& c : kCases) {
    const std::string path = outPath(c.file);
    saveVocabulary(v, path, c.format);
    VocabularyFormat expected = c.format;
    // DBoW2 and DBoW3 YAML share one loader, which reads all encodings.
    if (c.format == VocabularyFormat::kDbow2BriefYaml || c.format == VocabularyFormat::kDbow3Yaml) {
      expected = VocabularyFormat::kDbow2Yaml;
    }
    EXPECT_EQ(detectVocabularyFormat(path), expected) << c.file;
  }
  // Content wins over the extension: a .bowgvoc saved under a .txt name.
  saveVocabulary(v, outPath("misnamed.txt"), VocabularyFormat::kBowg);
  EXPECT_EQ(detectVocabularyFormat(outPath("misnamed.txt")), VocabularyFormat::kBowg);
  writeAll(outPath("garbage.dat"), "hello world, no vocabulary here\n");
  EXPECT_THROW(loadVocabulary(outPath("garbage.dat")), FormatError);
}

TEST(VocabularyIo, MissingFileIsIoErrorNamingThePath) {
  const std::string path = outPath("does_not_exist.bowgvoc");
  try {
    loadVocabulary(path);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(saveVocabulary(testing::makeSyntheticVocabulary(2, 1), "/nonexistent_dir/x.bowgvoc"),
               IoError);
}

TEST(VocabularyIo, BriefBitStringIsMostSignificantBitFirst) {
  // boost::to_string prints bit 255 first: a string starting with '1' and
  // otherwise '0' is bit 255 = bit 63 of block 3; ending with '1' is bit 0.
  std::string first(256, '0'), last(256, '0');
  first[0] = '1';
  last[255] = '1';
  const std::string yaml =
      "%YAML:1.0\n---\nvocabulary:\n   k: 2\n   L: 1\n   scoringType: 1\n   weightingType: 2\n"
      "   nodes:\n"
      "      - { nodeId:1, parentId:0, weight:0.5, descriptor:\"" +
      first +
      "\" }\n"
      "      - { nodeId:2, parentId:0, weight:1.5, descriptor:\"" +
      last +
      "\" }\n"
      "   words:\n      - { wordId:0, nodeId:1 }\n      - { wordId:1, nodeId:2 }\n";
  writeAll(outPath("brief_hand.yml"), yaml);
  const Vocabulary v = loadVocabulary(outPath("brief_hand.yml"));
  EXPECT_EQ(v.nodes()[1].descriptor.bits[3], 1ull << 63);
  EXPECT_EQ(v.nodes()[1].descriptor.bits[0], 0u);
  EXPECT_EQ(v.nodes()[2].descriptor.bits[0], 1u);
  EXPECT_EQ(v.scoring(), ScoringType::kL2);
  EXPECT_EQ(v.weighting(), WeightingType::kIdf);
  EXPECT_DOUBLE_EQ(v.wordWeight(1), 1.5);
}

TEST(VocabularyIo, OrbBytesAreLittleEndianBlocks) {
  // DBoW2 ORB string: byte 0 = 1 -> bit 0; byte 31 = 128 -> bit 255.
  std::string a = "1", b = "0";
  for (int j = 1; j < 32; ++j) {
    a += " 0";
    b += j == 31 ? " 128" : " 0";
  }
  const std::string yaml =
      "%YAML:1.0\n---\nvocabulary:\n   k: 2\n   L: 1\n   scoringType: 0\n   weightingType: 0\n"
      "   nodes:\n"
      "      - { nodeId:1, parentId:0, weight:0., descriptor:\"" +
      a +
      " \" }\n"
      "      - { nodeId:2, parentId:0, weight:0., descriptor:\"dbw3 0 32 " +
      b +
      " \" }\n"
      "   words:\n      - { wordId:0, nodeId:1 }\n      - { wordId:1, nodeId:2 }\n";
  writeAll(outPath("orb_hand.yml"), yaml);
  const Vocabulary v = loadVocabulary(outPath("orb_hand.yml"));
  EXPECT_EQ(v.nodes()[1].descriptor.bits[0], 1u);
  EXPECT_EQ(v.nodes()[2].descriptor.bits[3], 1ull << 63);
}

TEST(VocabularyIo, VinsBlocksMapOneToOne) {
  // Hand-made VINS file: k 2, L 1, 2 nodes, 2 words; node 1 blocks {1,0,0,0},
  // node 2 blocks {0,0,0,2^63}.
  std::string bin;
  auto put = [&](std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bin.push_back(static_cast<char>(v >> (8 * i)));
  };
  for (int v : {2, 1, 0, 0, 2, 2}) put(static_cast<std::uint32_t>(v), 4);
  put(1, 4), put(0, 4), put(0, 8), put(1, 8), put(0, 8), put(0, 8), put(0, 8);
  put(2, 4), put(0, 4), put(0, 8), put(0, 8), put(0, 8), put(0, 8), put(1ull << 63, 8);
  put(1, 4), put(0, 4), put(2, 4), put(1, 4);
  writeAll(outPath("hand.bin"), bin);
  const Vocabulary v = loadVocabulary(outPath("hand.bin"));
  EXPECT_EQ(v.nodes()[1].descriptor.bits[0], 1u);
  EXPECT_EQ(v.nodes()[2].descriptor.bits[3], 1ull << 63);
  EXPECT_EQ(v.nodes()[1].word, 0u);
  EXPECT_EQ(v.nodes()[2].word, 1u);
}

TEST(VocabularyIo, ForeignNodeOrderIsRebuiltIntoOurLayout) {
  // ORB-SLAM-like tree whose children are not consecutive in the file:
  // root -> {1, 3}, 1 -> {2, 4}. Our layout renumbers breadth-first:
  // 0 -> {1, 2}, 1 -> {3, 4}; words follow their nodes.
  std::string zeros;
  for (int j = 0; j < 32; ++j) zeros += " 0";
  std::string ones;
  for (int j = 0; j < 32; ++j) ones += " 255";
  const std::string txt = "2 2 0 0\n0 0" + zeros + " 0\n1 1" + zeros + " 0.5\n0 1" + ones +
                          " 1.5\n1 1" + ones + " 2.5\n";
  writeAll(outPath("reorder_ORBvoc.txt"), txt);
  const Vocabulary v = loadVocabulary(outPath("reorder_ORBvoc.txt"));
  ASSERT_EQ(v.nodeCount(), 5u);
  EXPECT_EQ(v.nodes()[0].first_child, 1u);
  EXPECT_EQ(v.nodes()[2].word, 1u);  // file node 3 (word 1, weight 1.5)
  EXPECT_DOUBLE_EQ(v.nodes()[2].weight, 1.5);
  EXPECT_EQ(v.nodes()[3].word, 0u);  // file node 2
  EXPECT_EQ(v.nodes()[4].word, 2u);  // file node 4
  EXPECT_EQ(v.nodes()[4].parent, 1u);
}

TEST(VocabularyIo, RefusesCompressedDbow3AndHugeCounts) {
  std::string bin;
  auto put = [&](std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bin.push_back(static_cast<char>(v >> (8 * i)));
  };
  put(88877711233ull, 8);
  put(1, 1);
  put(1000, 4);
  writeAll(outPath("compressed.dbow3"), bin);
  try {
    loadVocabulary(outPath("compressed.dbow3"));
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("QuickLZ"), std::string::npos) << e.what();
  }
  // DBoW3 claiming 4e9 nodes in a 30-byte file.
  bin[8] = 0;
  bin[9] = bin[10] = bin[11] = bin[12] = '\xff';
  bin += std::string(16, '\0');
  writeAll(outPath("huge.dbow3"), bin);
  EXPECT_THROW(loadVocabulary(outPath("huge.dbow3")), FormatError);
  // .bowgvoc whose header claims 2^60 nodes.
  saveVocabulary(testing::makeSyntheticVocabulary(2, 1), outPath("huge.bowgvoc"));
  std::string b = readAll(outPath("huge.bowgvoc"));
  b[32 + 7] = 0x10;
  writeAll(outPath("huge.bowgvoc"), b);
  EXPECT_THROW(loadVocabulary(outPath("huge.bowgvoc")), FormatError);
}

// Every mutation must give a clean FormatError/IoError or a vocabulary that
// is usable (the constructor validated it).

}  // namespace
}  // namespace bowg
