// The tree descent: the nearest child and the first of equally near ones on
// hand-built one-level trees (distances chosen by hand, ties within and
// across groups of eight children), and the AVX2 descent against the
// portable one, node for node, on full trees of 2-17 children a node.
#include "vocabulary/tree_descent.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "core/cpu_features.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

using Node = Vocabulary::Node;

// A descriptor with the lowest `bits` bits set: at that Hamming distance
// from all zeros.
Descriptor withBits(int bits) {
  Descriptor d;
  for (int b = 0; b < bits; ++b) d.bits[b / 64] |= 1ULL << (b % 64);
  return d;
}

// Root -> one leaf per distance, leaf c (word c) at distances[c] from zero.
Vocabulary oneLevel(const std::vector<int>& distances) {
  std::vector<Node> nodes(distances.size() + 1);
  nodes[0].first_child = 1;
  nodes[0].num_children = static_cast<std::uint32_t>(distances.size());
  for (std::size_t c = 0; c < distances.size(); ++c) {
    Node& n = nodes[c + 1];
    n.level = 1;
    n.word = static_cast<WordId>(c);
    n.weight = 1.0;
    n.descriptor = withBits(distances[c]);
  }
  return Vocabulary(static_cast<int>(distances.size()), 1, WeightingType::kTfIdf,
                    ScoringType::kL1, std::move(nodes));
}

// The word all-zero descriptors reach through `descend`.
WordId zeroWord(const Vocabulary& v, tree_descent::DescendBatch descend) {
  const std::vector<Descriptor> zeros(3);
  WordId words[tree_descent::kBatch];
  NodeId at_level[tree_descent::kBatch];
  descend(v.nodes().data(), zeros.data(), zeros.size(), 1, words, at_level);
  EXPECT_EQ(words[0], words[2]);
  EXPECT_EQ(at_level[0], words[0] + 1);  // the leaf itself is at level 1
  return words[0];
}

std::vector<tree_descent::DescendBatch> descents() {
  std::vector<tree_descent::DescendBatch> d{tree_descent::descendBatchPortable};
  if (cpuHasAvx2()) d.push_back(tree_descent::descendBatchAvx2);
  return d;
}

TEST(TreeDescent, NearestChildAndFirstOfEquals) {
  for (const tree_descent::DescendBatch descend : descents()) {
    // Nearest unique: distance 2 at child 3.
    EXPECT_EQ(zeroWord(oneLevel({9, 7, 5, 2, 8}), descend), 3u);
    // Ties: 3 at children 1 and 4: the first.
    EXPECT_EQ(zeroWord(oneLevel({6, 3, 9, 4, 3, 5}), descend), 1u);
    // Twelve children: the nearest (3, twice) both in the second eight.
    EXPECT_EQ(zeroWord(oneLevel({9, 7, 7, 12, 5, 8, 5, 6, 5, 9, 3, 3}), descend), 10u);
    // A tie across the eights: 4 at children 3 and 9: the first.
    EXPECT_EQ(zeroWord(oneLevel({5, 8, 6, 4, 7, 9, 5, 6, 7, 4, 8}), descend), 3u);
    // The last of seventeen, and distances beyond a byte and at 256.
    EXPECT_EQ(zeroWord(oneLevel({256, 200, 180, 170, 160, 150, 140, 130, 129, 128, 127, 126, 125,
                                 124, 123, 122, 121}),
                       descend),
              16u);
    EXPECT_EQ(zeroWord(oneLevel({256, 255}), descend), 1u);
    EXPECT_EQ(zeroWord(oneLevel({0, 0}), descend), 0u);
  }
}

TEST(TreeDescent, TheAvx2DescentReachesThePortableOnesNodes) {
  if (!cpuHasAvx2()) {
    GTEST_SKIP() << "this CPU has no AVX2: only the portable descent runs here";
  }
  std::mt19937_64 rng(12);
  for (const int k : {2, 3, 5, 8, 9, 10, 16, 17}) {
    const int depth = k <= 5 ? 4 : 3;
    const Vocabulary v = testing::makeSyntheticVocabulary(k, depth, static_cast<std::uint64_t>(k));
    // Random descriptors, and ones a few bits from a node's (many ties).
    std::vector<Descriptor> d = testing::randomDescriptors(400, static_cast<std::uint64_t>(k));
    for (int i = 0; i < 400; ++i) {
      Descriptor near = v.nodes()[1 + rng() % (v.nodes().size() - 1)].descriptor;
      for (int flips = static_cast<int>(rng() % 4); flips > 0; --flips) {
        const int bit = static_cast<int>(rng() % 256);
        near.bits[bit / 64] ^= 1ULL << (bit % 64);
      }
      d.push_back(near);
    }
    for (int level = 0; level <= depth; ++level) {
      for (std::size_t i = 0; i < d.size(); i += tree_descent::kBatch) {
        const std::size_t count = std::min(tree_descent::kBatch, d.size() - i);
        WordId wp[tree_descent::kBatch], wa[tree_descent::kBatch];
        NodeId np[tree_descent::kBatch], na[tree_descent::kBatch];
        tree_descent::descendBatchPortable(v.nodes().data(), d.data() + i, count, level, wp, np);
        tree_descent::descendBatchAvx2(v.nodes().data(), d.data() + i, count, level, wa, na);
        for (std::size_t g = 0; g < count; ++g) {
          ASSERT_EQ(wa[g], wp[g]) << "k " << k << " descriptor " << i + g;
          ASSERT_EQ(na[g], np[g]) << "k " << k << " level " << level;
          // The one-descriptor descent of Vocabulary agrees too.
          NodeId at = 0;
          ASSERT_EQ(v.transform(d[i + g], &at, std::max(level, 1)), wp[g]);
          if (level >= 1) ASSERT_EQ(at, np[g]);
        }
      }
    }
  }
}

TEST(TreeDescent, TheBestDescentIsTheFastestTheCpuRuns) {
  EXPECT_EQ(tree_descent::bestDescendBatch(),
            cpuHasAvx2() ? tree_descent::descendBatchAvx2 : tree_descent::descendBatchPortable);
}

}  // namespace
}  // namespace bowg
