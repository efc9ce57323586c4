// Vocabulary training: options, determinism, k-medians on clusters we can
// reason about, IDF weights worked out by hand, degenerate inputs.
#include "bowg/vocabulary/vocabulary_trainer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "bowg/core/errors.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

// A noisy copy of `d`: `flips` distinct random bits inverted.
Descriptor noisy(const Descriptor& d, int flips, std::mt19937_64& rng) {
  Descriptor out = d;
  std::vector<int> used;
  while (static_cast<int>(used.size()) < flips) {
    const int bit = static_cast<int>(rng() % 256);
    if (std::find(used.begin(), used.end(), bit) != used.end()) continue;
    used.push_back(bit);
    out.bits[bit / 64] ^= 1ull << (bit % 64);
  }
  return out;
}

std::vector<std::vector<Descriptor>> randomImages(int images, int per_image, std::uint64_t seed) {
  std::vector<std::vector<Descriptor>> out;
  for (int i = 0; i < images; ++i) out.push_back(testing::randomDescriptors(per_image, seed + i));
  return out;
}

TEST(TrainingOptions, ValidateNamesTheField) {
  auto expectBad = [](TrainingOptions o, const std::string& field) {
    try {
      o.validate();
      FAIL() << field;
    } catch (const InvalidParameter& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  TrainingOptions o;
  EXPECT_NO_THROW(o.validate());
  o.k = 1;
  expectBad(o, "training.k");
  // Beyond what the vocabulary loaders accept: it could not be saved.
  o.k = 1001;
  expectBad(o, "training.k: must be <= 1000");
  o.k = 1000;
  EXPECT_NO_THROW(o.validate());
  o = TrainingOptions();
  o.L = 0;
  expectBad(o, "training.L");
  o = TrainingOptions();
  o.max_iterations = 0;
  expectBad(o, "training.max_iterations");
  o = TrainingOptions();
  o.threads = 0;
  expectBad(o, "training.threads");
  o = TrainingOptions();
  o.weighting = static_cast<WeightingType>(9);
  expectBad(o, "training.weighting");
}

TEST(VocabularyTrainer, RefusesNoDescriptors) {
  EXPECT_THROW(trainVocabulary({}, TrainingOptions()), std::invalid_argument);
  EXPECT_THROW(trainVocabulary({{}, {}}, TrainingOptions()), std::invalid_argument);
}

TEST(VocabularyTrainer, DeterministicForASeedAndThreadCount) {
  const auto images = randomImages(20, 300, 5);
  TrainingOptions o;
  o.k = 5;
  o.L = 3;
  o.seed = 7;
  o.threads = 1;
  const Vocabulary a = trainVocabulary(images, o);
  const Vocabulary b = trainVocabulary(images, o);
  o.threads = 2;
  const Vocabulary c = trainVocabulary(images, o);
  EXPECT_EQ(a.fingerprint(), b.fingerprint());
  EXPECT_EQ(a.fingerprint(), c.fingerprint());
  o.seed = 8;
  EXPECT_NE(trainVocabulary(images, o).fingerprint(), a.fingerprint());
}

TEST(VocabularyTrainer, RecoversWellSeparatedClustersAsMajorityCentres) {
  // Four random prototypes (pairwise ~128 bits apart) and 40 copies of each
  // with 3 flipped bits. A bit of a centre is wrong only if >= 20 of its 40
  // members flipped that very bit: the centres must be the prototypes.
  std::mt19937_64 rng(3);
  std::vector<Descriptor> protos = testing::randomDescriptors(4, 99);
  std::vector<std::vector<Descriptor>> images(10);
  for (int copy = 0; copy < 40; ++copy) {
    for (int p = 0; p < 4; ++p) images[copy % 10].push_back(noisy(protos[p], 3, rng));
  }
  TrainingOptions o;
  o.k = 4;
  o.L = 1;
  const Vocabulary v = trainVocabulary(images, o);
  ASSERT_EQ(v.wordCount(), 4u);
  std::vector<WordId> word_of_proto;
  for (const Descriptor& p : protos) {
    const WordId w = v.transform(p);
    EXPECT_EQ(v.nodes()[v.nodeOfWord(w)].descriptor, p);
    word_of_proto.push_back(w);
  }
  std::sort(word_of_proto.begin(), word_of_proto.end());
  EXPECT_EQ(std::unique(word_of_proto.begin(), word_of_proto.end()), word_of_proto.end());
}

TEST(VocabularyTrainer, IdfWeightsAreLogOfImageRatios) {
  // Clusters A, B, C, D (3 noisy copies per image where present):
  //   image 0: A B C   image 1: A B   image 2: A D   image 3: A
  // N = 4: idf(A) = log(4/4) = 0, idf(B) = log(4/2) = 0.6931,
  // idf(C) = idf(D) = log(4/1) = 1.3863.
  std::mt19937_64 rng(4);
  const std::vector<Descriptor> p = testing::randomDescriptors(4, 123);
  const std::vector<std::vector<int>> present = {{0, 1, 2}, {0, 1}, {0, 3}, {0}};
  std::vector<std::vector<Descriptor>> images;
  for (const auto& clusters : present) {
    images.emplace_back();
    for (int c : clusters) {
      for (int i = 0; i < 3; ++i) images.back().push_back(noisy(p[c], 2, rng));
    }
  }
  TrainingOptions o;
  o.k = 4;
  o.L = 1;
  const Vocabulary v = trainVocabulary(images, o);
  ASSERT_EQ(v.wordCount(), 4u);
  EXPECT_NEAR(v.wordWeight(v.transform(p[0])), 0.0, 1e-12);
  EXPECT_NEAR(v.wordWeight(v.transform(p[1])), std::log(2.0), 1e-12);
  EXPECT_NEAR(v.wordWeight(v.transform(p[2])), std::log(4.0), 1e-12);
  EXPECT_NEAR(v.wordWeight(v.transform(p[3])), std::log(4.0), 1e-12);
  // TF and BINARY store 1 (DBoW2).
  o.weighting = WeightingType::kBinary;
  const Vocabulary b = trainVocabulary(images, o);
  for (WordId w = 0; w < b.wordCount(); ++w) EXPECT_DOUBLE_EQ(b.wordWeight(w), 1.0);
}

TEST(VocabularyTrainer, FewDescriptorsBecomeShallowLeaves) {
  // 3 descriptors, k = 4: each is its own child of the root (DBoW2), and
  // single descriptors are not split further although L = 3.
  const auto d = testing::randomDescriptors(3, 1);
  TrainingOptions o;
  o.k = 4;
  o.L = 3;
  const Vocabulary v = trainVocabulary({d}, o);
  EXPECT_EQ(v.nodeCount(), 4u);
  EXPECT_EQ(v.wordCount(), 3u);
  for (const Descriptor& x : d) EXPECT_EQ(v.nodes()[v.nodeOfWord(v.transform(x))].descriptor, x);
}

TEST(VocabularyTrainer, IdenticalDescriptorsStopSplitting) {
  const Descriptor d = testing::randomDescriptors(1, 2)[0];
  TrainingOptions o;
  o.k = 3;
  o.L = 4;
  const Vocabulary v = trainVocabulary({std::vector<Descriptor>(100, d)}, o);
  EXPECT_EQ(v.nodeCount(), 2u);  // root + one leaf
  EXPECT_EQ(v.wordCount(), 1u);
  // One image holding the only word: idf = log(1/1) = 0.
  EXPECT_DOUBLE_EQ(v.wordWeight(0), 0.0);
}

TEST(VocabularyTrainer, AnyBranchingAndDepth) {
  const auto images = randomImages(4, 250, 9);
  for (int k : {2, 3, 7}) {
    for (int L : {1, 2, 6}) {
      TrainingOptions o;
      o.k = k;
      o.L = L;
      o.max_iterations = 3;
      const Vocabulary v = trainVocabulary(images, o);
      EXPECT_EQ(v.branching(), k);
      EXPECT_EQ(v.depth(), L);
      EXPECT_LE(v.wordCount(), 1000u);
      for (const auto& n : v.nodes()) EXPECT_LE(n.num_children, static_cast<std::uint32_t>(k));
      // A full tree would have min(k^L, 1000) leaves; k-medians may leave
      // fewer (empty clusters, duplicate-free small nodes are exact).
      EXPECT_GE(v.wordCount(), std::min<std::size_t>(static_cast<std::size_t>(k), 1000u));
    }
  }
}

TEST(VocabularyTrainer, ReportsMonotoneProgressEndingAtOne) {
  std::vector<double> seen;
  TrainingOptions o;
  o.k = 3;
  o.L = 3;
  trainVocabulary(randomImages(3, 100, 1), o,
                  [&](double f, const std::string&) { seen.push_back(f); });
  ASSERT_FALSE(seen.empty());
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
}

}  // namespace
}  // namespace bowg
