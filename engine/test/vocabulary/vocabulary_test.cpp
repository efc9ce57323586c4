// Vocabulary tree: structure validation, descent, the four weighting schemes
// and the direct index, on a hand-built unbalanced tree whose results are
// worked out by hand below; plus the fingerprint.
#include "bowg/vocabulary/vocabulary.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

using Node = Vocabulary::Node;

Descriptor desc(std::uint64_t b0, std::uint64_t rest = 0) {
  Descriptor d;
  d.bits = {{b0, rest, rest, rest}};
  return d;
}
const std::uint64_t kOnes = ~0ull;

// k = 2, L = 2, unbalanced (node 2 is a leaf at depth 1):
//   0 root -> {1, 2}
//   1 (all zeros)            -> {3, 4}
//   2 (all ones)  word 2, idf 1.5
//   3 (all zeros) word 0, idf 0.5
//   4 (low byte set) word 1, idf 2.0
std::vector<Node> tinyNodes() {
  std::vector<Node> n(5);
  n[0].first_child = 1;
  n[0].num_children = 2;
  n[1].parent = 0;
  n[1].level = 1;
  n[1].first_child = 3;
  n[1].num_children = 2;
  n[1].descriptor = desc(0);
  n[2].parent = 0;
  n[2].level = 1;
  n[2].word = 2;
  n[2].weight = 1.5;
  n[2].descriptor = desc(kOnes, kOnes);
  n[3].parent = 1;
  n[3].level = 2;
  n[3].word = 0;
  n[3].weight = 0.5;
  n[3].descriptor = desc(0);
  n[4].parent = 1;
  n[4].level = 2;
  n[4].word = 1;
  n[4].weight = 2.0;
  n[4].descriptor = desc(0xff);
  return n;
}

Vocabulary tiny(WeightingType w = WeightingType::kTfIdf, ScoringType s = ScoringType::kL1,
                std::vector<Node> nodes = tinyNodes()) {
  return Vocabulary(2, 2, w, s, std::move(nodes));
}

// Image: x1 = zeros (word 0), x3 twice (word 1), x4 = ones (word 2).
std::vector<Descriptor> image() { return {desc(0), desc(0xff), desc(0xff), desc(kOnes, kOnes)}; }

void expectFormatError(std::vector<Node> nodes, const std::string& fragment, int k = 2) {
  try {
    Vocabulary v(k, 2, WeightingType::kTfIdf, ScoringType::kL1, std::move(nodes));
    FAIL() << "expected FormatError containing '" << fragment << "'";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Vocabulary, AcceptsValidUnbalancedTree) {
  const Vocabulary v = tiny();
  EXPECT_EQ(v.branching(), 2);
  EXPECT_EQ(v.depth(), 2);
  EXPECT_EQ(v.wordCount(), 3u);
  EXPECT_EQ(v.nodeCount(), 5u);
  EXPECT_EQ(v.nodeOfWord(2), 2u);
  EXPECT_DOUBLE_EQ(v.wordWeight(1), 2.0);
  EXPECT_FALSE(v.empty());
  EXPECT_TRUE(Vocabulary().empty());
}

TEST(Vocabulary, RejectsEachInconsistency) {
  auto n = tinyNodes();
  n[3].parent = 2;
  expectFormatError(n, "names 2 as its parent");
  n = tinyNodes();
  n[1].first_child = 4;
  expectFormatError(n, "out of bounds");
  n = tinyNodes();
  n[1].first_child = 1;
  expectFormatError(n, "cycle");
  n = tinyNodes();
  n[4].word = 0;
  expectFormatError(n, "word 0 is on both");
  n = tinyNodes();
  n[4].word = Vocabulary::kNoWord;
  expectFormatError(n, "has no word");
  n = tinyNodes();
  n[4].word = 7;
  expectFormatError(n, "ids must be 0..W-1");
  n = tinyNodes();
  n[3].level = 1;
  expectFormatError(n, "has level 1 but its parent");
  n = tinyNodes();
  n[1].word = 5;
  expectFormatError(n, "inner node 1 carries word");
  n = tinyNodes();
  n[0].num_children = 1;  // node 2 is no longer anybody's child
  expectFormatError(n, "node 2 is in no child range");
  expectFormatError(tinyNodes(), "k = 1 < 2", 1);
  n = tinyNodes();
  n[3].weight = std::nan("");
  expectFormatError(n, "non-finite weight");
  n = tinyNodes();
  n[3].weight = -1e300;
  expectFormatError(n, "negative weight");
  expectFormatError(std::vector<Node>(1), "no node below the root");
  // Three children under a k = 2 tree.
  n = tinyNodes();
  n.push_back(n[4]);
  n[1].num_children = 3;
  n[5].word = 3;
  expectFormatError(n, "more than k = 2");
}

TEST(Vocabulary, DescendsByMinimumHammingWithLowestIndexTies) {
  const Vocabulary v = tiny();
  EXPECT_EQ(v.transform(desc(0)), 0u);
  EXPECT_EQ(v.transform(desc(0xff)), 1u);
  EXPECT_EQ(v.transform(desc(kOnes, kOnes)), 2u);
  // 0x0f: 4 bits from node 3 and 4 bits from node 4: the tie goes to node 3.
  EXPECT_EQ(v.transform(desc(0x0f)), 0u);
  NodeId at = 99;
  EXPECT_EQ(v.transform(desc(0xff), &at, 1), 1u);
  EXPECT_EQ(at, 1u);  // ancestor at depth 1
  EXPECT_EQ(v.transform(desc(kOnes, kOnes), &at, 2), 2u);
  EXPECT_EQ(at, 2u);  // the leaf itself: shallower than depth 2
  EXPECT_THROW(v.transform(desc(0), &at, 0), std::invalid_argument);
}

TEST(Vocabulary, TfIdfWeighting) {
  // counts: w0 1, w1 2, w2 1 of n = 4 features; tf*idf = 0.25*0.5, 0.5*2, 0.25*1.5
  // = 0.125, 1.0, 0.375; L1 sum 1.5 -> 1/12, 2/3, 1/4.
  BowVector bow;
  std::vector<WordId> words;
  tiny().transform(image(), &bow, nullptr, 0, &words);
  ASSERT_EQ(bow.size(), 3u);
  EXPECT_EQ(bow[0].first, 0u);
  EXPECT_NEAR(bow[0].second, 1.0 / 12, 1e-12);
  EXPECT_NEAR(bow[1].second, 2.0 / 3, 1e-12);
  EXPECT_NEAR(bow[2].second, 0.25, 1e-12);
  EXPECT_EQ(words, (std::vector<WordId>{0, 1, 1, 2}));
}

TEST(Vocabulary, TfIdfWithoutNormalisationForDotProduct) {
  BowVector bow;
  tiny(WeightingType::kTfIdf, ScoringType::kDotProduct).transform(image(), &bow);
  ASSERT_EQ(bow.size(), 3u);
  EXPECT_NEAR(bow[0].second, 0.125, 1e-12);
  EXPECT_NEAR(bow[1].second, 1.0, 1e-12);
  EXPECT_NEAR(bow[2].second, 0.375, 1e-12);
}

TEST(Vocabulary, TfWeightingIgnoresIdf) {
  // tf = 1/4, 2/4, 1/4 (already L1-unit).
  BowVector bow;
  tiny(WeightingType::kTf).transform(image(), &bow);
  ASSERT_EQ(bow.size(), 3u);
  EXPECT_NEAR(bow[0].second, 0.25, 1e-12);
  EXPECT_NEAR(bow[1].second, 0.5, 1e-12);
  EXPECT_NEAR(bow[2].second, 0.25, 1e-12);
}

TEST(Vocabulary, IdfWeightingCountsEachWordOnce) {
  // DBoW2 (addIfNotExist): idf once per present word: 0.5, 2.0, 1.5, sum 4
  // -> 0.125, 0.5, 0.375.
  BowVector bow;
  tiny(WeightingType::kIdf).transform(image(), &bow);
  ASSERT_EQ(bow.size(), 3u);
  EXPECT_NEAR(bow[0].second, 0.125, 1e-12);
  EXPECT_NEAR(bow[1].second, 0.5, 1e-12);
  EXPECT_NEAR(bow[2].second, 0.375, 1e-12);
}

TEST(Vocabulary, BinaryWeightingWithL2) {
  // 1 per present word: (1, 1, 1) / sqrt(3).
  BowVector bow;
  tiny(WeightingType::kBinary, ScoringType::kL2).transform(image(), &bow);
  ASSERT_EQ(bow.size(), 3u);
  for (const auto& e : bow) EXPECT_NEAR(e.second, 1.0 / std::sqrt(3.0), 1e-12);
}

TEST(Vocabulary, ZeroWeightWordsAreStopped) {
  // idf(w0) = 0: w0 is dropped; 1.0 and 0.375 remain -> 1/1.375, 0.375/1.375.
  auto n = tinyNodes();
  n[3].weight = 0.0;
  BowVector bow;
  tiny(WeightingType::kTfIdf, ScoringType::kL1, n).transform(image(), &bow);
  ASSERT_EQ(bow.size(), 2u);
  EXPECT_EQ(bow[0].first, 1u);
  EXPECT_NEAR(bow[0].second, 1.0 / 1.375, 1e-12);
  EXPECT_NEAR(bow[1].second, 0.375 / 1.375, 1e-12);
}

TEST(Vocabulary, DirectIndexAtLevel) {
  const Vocabulary v = tiny();
  BowVector bow;
  DirectIndex direct;
  v.transform(image(), &bow, &direct, 1);
  // Level 1: features 0, 1, 2 under node 1; feature 3 on leaf 2. One
  // (node, feature) pair per feature, sorted by node, then feature.
  EXPECT_EQ(direct, (DirectIndex{{1, 0}, {1, 1}, {1, 2}, {2, 3}}));
  v.transform(image(), &bow, &direct, 2);
  // Level 2: node 2 (shallow leaf) {3}, node 3 {0}, node 4 {1, 2}.
  EXPECT_EQ(direct, (DirectIndex{{2, 3}, {3, 0}, {4, 1}, {4, 2}}));
}

TEST(Vocabulary, EmptyImageGivesEmptyOutputs) {
  BowVector bow{{1, 1.0}};
  DirectIndex direct{{1, 0}};
  std::vector<WordId> words{3};
  tiny().transform({}, &bow, &direct, 1, &words);
  EXPECT_TRUE(bow.empty());
  EXPECT_TRUE(direct.empty());
  EXPECT_TRUE(words.empty());
}

TEST(Vocabulary, FingerprintCoversContentButNotScoring) {
  Vocabulary a = tiny();
  const std::uint64_t fp = a.fingerprint();
  EXPECT_EQ(tiny().fingerprint(), fp);
  a.setScoring(ScoringType::kL2);
  EXPECT_EQ(a.fingerprint(), fp);
  EXPECT_EQ(tiny(WeightingType::kTfIdf, ScoringType::kChiSquare).fingerprint(), fp);
  EXPECT_NE(tiny(WeightingType::kIdf).fingerprint(), fp);
  auto n = tinyNodes();
  n[4].weight = 2.0000001;
  EXPECT_NE(tiny(WeightingType::kTfIdf, ScoringType::kL1, n).fingerprint(), fp);
  n = tinyNodes();
  n[4].descriptor.bits[3] ^= 1ull << 63;
  EXPECT_NE(tiny(WeightingType::kTfIdf, ScoringType::kL1, n).fingerprint(), fp);
  EXPECT_NE(Vocabulary(3, 2, WeightingType::kTfIdf, ScoringType::kL1, tinyNodes()).fingerprint(),
            fp);
}

TEST(Vocabulary, SyntheticFullTreeMapsNodeDescriptorsToTheirLeaves) {
  const Vocabulary v = testing::makeSyntheticVocabulary(4, 3, 7);
  EXPECT_EQ(v.wordCount(), 64u);
  EXPECT_EQ(v.nodeCount(), 1u + 4 + 16 + 64);
  // A leaf's own descriptor need not descend to it (its ancestors are
  // random), but the descent always ends on a leaf carrying that word.
  for (WordId w = 0; w < v.wordCount(); ++w) {
    const WordId got = v.transform(v.nodes()[v.nodeOfWord(w)].descriptor);
    EXPECT_EQ(v.nodes()[v.nodeOfWord(got)].num_children, 0u);
  }
}

TEST(Vocabulary, BatchedImageTransformAgreesWithSingleDescents) {
  // The image transform descends 8 descriptors in lockstep; it must give
  // exactly what one descent at a time gives, words and direct-index nodes.
  const Vocabulary v = testing::makeSyntheticVocabulary(5, 4, 3);
  const auto descriptors = testing::randomDescriptors(101, 4);  // not a multiple of 8
  for (int level : {1, 2, 4}) {
    BowVector bow;
    DirectIndex direct;
    std::vector<WordId> words;
    v.transform(descriptors, &bow, &direct, level, &words);
    ASSERT_EQ(words.size(), descriptors.size());
    std::vector<NodeId> node_of(descriptors.size(), 0);
    ASSERT_EQ(direct.size(), descriptors.size());
    ASSERT_TRUE(std::is_sorted(direct.begin(), direct.end()));
    for (const auto& pair : direct) node_of[pair.second] = pair.first;
    for (std::size_t i = 0; i < descriptors.size(); ++i) {
      NodeId node = 0;
      EXPECT_EQ(words[i], v.transform(descriptors[i], &node, level));
      EXPECT_EQ(node_of[i], node);
      EXPECT_EQ(v.nodes()[node].level, static_cast<std::uint32_t>(level));
    }
  }
}

}  // namespace
}  // namespace bowg
