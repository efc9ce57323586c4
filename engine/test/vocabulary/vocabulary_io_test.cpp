// Vocabulary files: round trips through every format (same fingerprint),
// format detection, bit orders of the foreign formats, clear errors, and a
// fuzz of truncations and byte flips that must end in a clean exception or a
// valid vocabulary (run it under -DBOWG_SANITIZE=ON too).
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

namespace bowg {
namespace {

std::string outPath(const std::string& name) {
  return std::string(BOWG_TEST_OUTPUT_DIR) + "/vocio_" + name;
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeAll(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

struct FormatCase {
  VocabularyFormat format;
  const char* file;
};
const FormatCase kCases[] = {
    {VocabularyFormat::kBowg, "v.bowgvoc"},
    {VocabularyFormat::kDbow2Yaml, "v_dbow2.yml"},
    {VocabularyFormat::kDbow2Yaml, "v_dbow2.yml.gz"},
    {VocabularyFormat::kDbow2BriefYaml, "v_brief.yml"},
    {VocabularyFormat::kDbow3Yaml, "v_dbow3.yml.gz"},
    {VocabularyFormat::kDbow3Binary, "v.dbow3"},
    {VocabularyFormat::kOrbSlamText, "v_ORBvoc.txt"},
    {VocabularyFormat::kVinsBinary, "v_brief.bin"},
};

// An unbalanced trained-like tree: k = 3, L = 3, with one shallow leaf.
Vocabulary unbalanced(WeightingType w = WeightingType::kIdf,
                      ScoringType s = ScoringType::kChiSquare) {
  const Vocabulary full = testing::makeSyntheticVocabulary(3, 3, 11, w, s);
  // Cut the subtree of node 1 (level 1): keep its first child only... simpler:
  // rebuild with node 2 turned into a leaf by dropping its children.
  std::vector<Vocabulary::Node> nodes;
  const auto& src = full.nodes();
  std::vector<NodeId> map(src.size(), Vocabulary::kNoWord);
  // Breadth-first copy skipping the descendants of node 2.
  std::vector<NodeId> queue{0};
  map[0] = 0;
  nodes.push_back(src[0]);
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const NodeId old = queue[head];
    const NodeId now = map[old];
    if (old == 2) {
      nodes[now].num_children = 0;
      nodes[now].first_child = 0;
      continue;
    }
    if (src[old].num_children == 0) continue;
    nodes[now].first_child = static_cast<std::uint32_t>(nodes.size());
    for (std::uint32_t c = src[old].first_child; c < src[old].first_child + src[old].num_children;
         ++c) {
      map[c] = static_cast<NodeId>(nodes.size());
      Vocabulary::Node child = src[c];
      child.parent = now;
      nodes.push_back(child);
      queue.push_back(c);
    }
  }
  WordId word = 0;
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    nodes[i].word = nodes[i].num_children == 0 ? word++ : Vocabulary::kNoWord;
    if (nodes[i].num_children == 0 && nodes[i].weight == 0.0) nodes[i].weight = 0.25 * i;
  }
  return Vocabulary(3, 3, w, s, std::move(nodes));
}

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
void expectCleanOutcome(const std::string& path, const std::string& what, int* ok, int* rejected) {
  try {
    const Vocabulary v = loadVocabulary(path);
    ASSERT_FALSE(v.empty()) << what;
    BowVector bow;
    v.transform(testing::randomDescriptors(5, 3), &bow);
    ++*ok;
  } catch (const FormatError&) {
    ++*rejected;
  } catch (const IoError&) {
    ++*rejected;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": unexpected exception " << e.what();
  }
}

TEST(VocabularyIo, TruncatedAndCorruptedFilesFailCleanly) {
  const Vocabulary v = unbalanced(WeightingType::kTfIdf, ScoringType::kL1);
  std::mt19937 rng(42);
  for (const auto& c : kCases) {
    SCOPED_TRACE(c.file);
    const std::string good = outPath(c.file);
    saveVocabulary(v, good, c.format);
    const std::string bytes = readAll(good);
    // Keep the extension: detection falls back on it for VINS.
    const std::string bad = outPath(std::string("fuzz_") + c.file);
    int ok = 0, rejected = 0;
    const std::size_t step = std::max<std::size_t>(1, bytes.size() / 150);
    for (std::size_t cut = 0; cut < bytes.size(); cut += step) {
      writeAll(bad, bytes.substr(0, cut));
      expectCleanOutcome(bad, "truncated at " + std::to_string(cut), &ok, &rejected);
    }
    for (int trial = 0; trial < 150; ++trial) {
      std::string flipped = bytes;
      const std::size_t at = rng() % flipped.size();
      flipped[at] = static_cast<char>(flipped[at] ^ static_cast<char>(1 + rng() % 255));
      writeAll(bad, flipped);
      expectCleanOutcome(bad, "byte " + std::to_string(at) + " flipped", &ok, &rejected);
    }
    EXPECT_GT(rejected, 0);
    // Every truncation of our checksummed format is rejected; so is every flip.
    if (c.format == VocabularyFormat::kBowg) EXPECT_EQ(ok, 0);
  }
}

// Files that cv::FileStorage could not read safely, as the project writes
// them itself: the loader must refuse each with a FormatError naming the file
// and the line, never hang (OpenCV's parser spun for ever on the first) and
// never let another exception out (the second made OpenCV throw
// std::length_error).
void expectRefusedNaming(const std::string& name, const std::string& bytes,
                         const std::string& why) {
  const std::string path = outPath(name);
  writeAll(path, bytes);
  try {
    loadVocabulary(path);
    ADD_FAILURE() << name << " accepted";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
  }
}

TEST(VocabularyIo, MalformedYamlIsRefusedWithTheFileAndLine) {
  // 98 bytes found by fuzzing: OpenCV's parser never returned on them.
  const char hang[] =
      "%YAML:1.0\n weightingType:(0\ne\0   nodes:\n            - { nodeIdtIiptor:dbw3 0 32 33 7 "
      ":01 2[ nodeI }\n";
  expectRefusedNaming("hang.yml", std::string(hang, sizeof(hang) - 1), "no 'vocabulary' map");
  // An inline map with an empty key.
  expectRefusedNaming("empty_key.yml",
                      "%YAML:1.0\n---\nvocabulary:\n   k: 3\n   L: 2\n   scoringType: 0\n"
                      "   weightingType: 0\n   nodes:\n      - { :rdIdwo6, nodeId:10 }\n",
                      "line 9: expected a key in 'nodes', found ':'");
  const std::string head =
      "%YAML:1.0\n---\nvocabulary:\n   k: 2\n   L: 1\n   scoringType: 0\n   weightingType: 0\n";
  const std::string d = "\"dbw3 0 32" + std::string(32 * 2, ' ') + "\"";
  expectRefusedNaming("unterminated.yml", head + "   nodes:\n      - { nodeId:1, descriptor:\"1 2",
                      "line 9: unterminated quoted string");
  expectRefusedNaming("unknown_key.yml", head + "   colour: 3\n", "line 8: unknown key 'colour'");
  expectRefusedNaming("twice.yml", head + "   k: 2\n", "line 8: 'k' appears twice");
  expectRefusedNaming("not_integer.yml",
                      head + "   nodes:\n      - { nodeId:1x, parentId:0, weight:0., descriptor:" +
                          d + " }\n   words: []\n",
                      "'nodes[0].nodeId' is not an integer");
  expectRefusedNaming("missing_field.yml",
                      head + "   nodes:\n      - { nodeId:1, weight:0., descriptor:" + d +
                          " }\n   words: []\n",
                      "line 9: missing 'nodes[0].parentId'");
  expectRefusedNaming("no_words.yml", head + "   nodes: []\n", "missing 'words' sequence");
  expectRefusedNaming("deep.yml", head + "   nodes:\n      - { nodeId:{ a:1 } }\n",
                      "'nodeId' has no value");
  // Not a single byte of a vocabulary: still named, still a FormatError.
  expectRefusedNaming("binary.yml", std::string("%YAML\0\1\2{{{[[[", 14), "no 'vocabulary' map");
}

TEST(VocabularyIo, FlowSequencesAndQuotedDescriptorsAreRead) {
  // The same tree as a block sequence with unquoted descriptors (OpenCV's
  // output) and as flow sequences with quoted ones: one vocabulary.
  const Vocabulary v = testing::makeSyntheticVocabulary(2, 1);
  saveVocabulary(v, outPath("block.yml"), VocabularyFormat::kDbow3Yaml);
  std::string text = readAll(outPath("block.yml"));
  // Rewrite "- { ... descriptor:dbw3 ... }" items into a flow sequence with
  // quoted descriptors by hand.
  std::istringstream in(text);
  std::string line, out, items;
  bool in_nodes = false;
  while (std::getline(in, line)) {
    if (line.find("nodes:") != std::string::npos) {
      in_nodes = true;
      out += "   nodes: [\n";
      continue;
    }
    if (line.find("words:") != std::string::npos) {
      in_nodes = false;
      out += "   ]\n" + line + "\n";
      continue;
    }
    if (in_nodes) {
      const std::size_t at = line.find("descriptor:");
      if (at != std::string::npos) {
        const std::size_t close = line.rfind('}');
        line = line.substr(0, at) + "descriptor:\"" + line.substr(at + 11, close - at - 11) +
               "\" },";
      }
      const std::size_t dash = line.find("- {");
      if (dash != std::string::npos) line.replace(dash, 1, " ");
    }
    out += line + "\n";
  }
  writeAll(outPath("flow.yml"), out);
  const Vocabulary block = loadVocabulary(outPath("block.yml"));
  const Vocabulary flowed = loadVocabulary(outPath("flow.yml"));
  EXPECT_EQ(block.fingerprint(), v.fingerprint());
  EXPECT_EQ(flowed.fingerprint(), v.fingerprint()) << out;
}

// --- Third-party vocabularies in /work/shared/data (skipped when absent) ---

std::string sharedVocabulary(const std::string& name) {
  return std::string(BOWG_SHARED_DATA_DIR) + "/vocabularies/" + name;
}

bool exists(const std::string& path) { return std::ifstream(path).good(); }

void checkForeign(const std::string& name, int k, int L, std::size_t words) {
  const std::string path = sharedVocabulary(name);
  if (!exists(path)) GTEST_SKIP() << path << " is absent (shared third-party data)";
  const Vocabulary v = loadVocabulary(path);
  EXPECT_EQ(v.branching(), k);
  EXPECT_EQ(v.depth(), L);
  EXPECT_EQ(v.wordCount(), words);
  EXPECT_EQ(v.scoring(), ScoringType::kL1);
  EXPECT_EQ(v.weighting(), WeightingType::kTfIdf);
  // A word's own descriptor descends to that word unless the centre of a
  // sibling of one of its ancestors is closer on the way down (a k-medians
  // tree gives no guarantee). Measured: 608/722 (84 %) for the DBoW2 file,
  // 4067/4983 (82 %) for the DBoW3 file; a wrong byte order or node
  // relabelling would drop this to ~0.
  std::size_t own = 0;
  for (WordId w = 0; w < v.wordCount(); ++w) {
    if (v.transform(v.nodes()[v.nodeOfWord(w)].descriptor) == w) ++own;
  }
  EXPECT_GT(own, v.wordCount() * 3 / 4) << own << " of " << v.wordCount();
  // Among its siblings, a leaf's own descriptor is always the nearest
  // (distance 0), so the last step of the descent must find it.
  for (WordId w = 0; w < v.wordCount(); ++w) {
    const auto& leaf = v.nodes()[v.nodeOfWord(w)];
    const auto& parent = v.nodes()[leaf.parent];
    int best = 257;
    for (std::uint32_t c = parent.first_child; c < parent.first_child + parent.num_children; ++c) {
      best = std::min(best, hammingDistance(leaf.descriptor, v.nodes()[c].descriptor));
    }
    ASSERT_EQ(best, 0) << "word " << w;
  }
  // Every format keeps everything (the files' words are numbered in leaf
  // order, which is all ORB-SLAM's text can express).
  for (const auto& c : kCases) {
    const std::string out = outPath(name + "." + c.file);
    saveVocabulary(v, out, c.format);
    EXPECT_EQ(loadVocabulary(out).fingerprint(), v.fingerprint()) << c.file;
  }
}

TEST(VocabularyIoSharedData, Dbow2SmallVocabulary) {
  // k = 9, L = 3, words 0..721 (the file's last word entry is wordId 721).
  checkForeign("dbow2_orb_k9L3_small_voc.yml.gz", 9, 3, 722);
  if (HasFatalFailure() || IsSkipped()) return;
  // DBoW2 numbers children consecutively, so the file's node ids are kept:
  // the file lists "{ wordId:0, nodeId:19 }".
  EXPECT_EQ(loadVocabulary(sharedVocabulary("dbow2_orb_k9L3_small_voc.yml.gz")).nodeOfWord(0), 19u);
}

TEST(VocabularyIoSharedData, Dbow3Vocabulary) {
  // k = 10, L = 5, words 0..4982.
  checkForeign("dbow3_orb_k10L5_vocabulary.yml.gz", 10, 5, 4983);
}

TEST(VocabularyIoSharedData, BadInputsAreRefusedNamingTheFile) {
  const std::string dir = std::string(BOWG_SHARED_DATA_DIR) + "/bad_inputs/";
  if (!exists(dir + "hang_98.yml")) GTEST_SKIP() << dir << " is absent (shared data)";
  for (const char* name : {"hang_98.yml", "empty_key.yml", "negative_idf_vins.bin"}) {
    SCOPED_TRACE(name);
    try {
      loadVocabulary(dir + name);
      ADD_FAILURE() << "accepted";
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace bowg
