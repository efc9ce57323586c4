// TreeStreamCheck, the .bowgvoc loader's chunk-by-chunk tree check, against
// Vocabulary's constructor: the same verdict and word table on valid trees
// and on every single-field fault of two small trees, whatever the chunks;
// a fault only the range total catches; and the loader still naming the
// constructor's fault in a file whose checksum was resealed.
#include "vocabulary/tree_stream_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "core/resealed_checksum.h"
#include "synthetic_vocabulary.h"
#include "vocabulary_files.h"

namespace bowg {
namespace {

using Node = Vocabulary::Node;

bool constructorAccepts(int k, int L, const std::vector<Node>& nodes) {
  try {
    Vocabulary v(k, L, WeightingType::kTfIdf, ScoringType::kL1, nodes);
    return true;
  } catch (const FormatError&) {
    return false;
  }
}

// The loader's order: each chunk appended, then checked.
TreeStreamCheck streamed(int k, int L, const std::vector<Node>& nodes, std::size_t chunk) {
  TreeStreamCheck check(k, L, nodes.size());
  Vocabulary::NodeArray array;
  for (std::size_t begin = 0; begin < nodes.size(); begin += chunk) {
    const std::size_t end = std::min(nodes.size(), begin + chunk);
    array.insert(array.end(), nodes.begin() + static_cast<std::ptrdiff_t>(begin),
                 nodes.begin() + static_cast<std::ptrdiff_t>(end));
    check.consume(array, begin, end);
  }
  return check;
}

std::vector<Node> nodesOf(const Vocabulary& v) {
  return std::vector<Node>(v.nodes().begin(), v.nodes().end());
}

TEST(TreeStreamCheck, ValidTreesPassWithTheConstructorsWordTable) {
  for (const Vocabulary& v :
       {testing::makeSyntheticVocabulary(3, 3, 5), testing::unbalanced()}) {
    for (const std::size_t chunk : {std::size_t{1}, std::size_t{3}, std::size_t{16}, v.nodeCount()}) {
      TreeStreamCheck check = streamed(3, 3, nodesOf(v), chunk);
      ASSERT_TRUE(check.passed()) << "chunk " << chunk;
      const std::vector<NodeId> words = check.takeWordToNode();
      ASSERT_EQ(words.size(), v.wordCount());
      for (WordId w = 0; w < words.size(); ++w) EXPECT_EQ(words[w], v.nodeOfWord(w)) << w;
    }
  }
}

// Every field of every node set to values near the node, its relatives and
// the tree's bounds: the stream passes exactly what the constructor accepts.
TEST(TreeStreamCheck, AgreesWithTheConstructorOnEverySingleFieldFault) {
  for (const Vocabulary& v :
       {testing::makeSyntheticVocabulary(3, 3, 5), testing::unbalanced()}) {
    const std::vector<Node> good = nodesOf(v);
    const std::uint32_t n = static_cast<std::uint32_t>(good.size());
    int rejected = 0, cases = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      for (int field = 0; field < 5; ++field) {
        std::uint32_t* slot[5] = {nullptr, nullptr, nullptr, nullptr, nullptr};
        std::vector<Node> nodes = good;
        slot[0] = &nodes[i].parent;
        slot[1] = &nodes[i].first_child;
        slot[2] = &nodes[i].num_children;
        slot[3] = &nodes[i].level;
        slot[4] = &nodes[i].word;
        const std::uint32_t was = *slot[field];
        for (const std::uint32_t value :
             {0u, 1u, 2u, 3u, 4u, was - 1, was + 1, i - 1, i, i + 1, n - 2, n - 1, n,
              Vocabulary::kNoWord}) {
          if (value == was) continue;
          *slot[field] = value;
          const bool accepted = constructorAccepts(3, 3, nodes);
          EXPECT_EQ(streamed(3, 3, nodes, 7).passed(), accepted)
              << "node " << i << " field " << field << " = " << value;
          rejected += accepted ? 0 : 1;
          ++cases;
        }
      }
      for (const double weight : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        std::vector<Node> nodes = good;
        nodes[i].weight = weight;
        EXPECT_FALSE(streamed(3, 3, nodes, 7).passed()) << "node " << i << " weight " << weight;
        EXPECT_FALSE(constructorAccepts(3, 3, nodes));
      }
    }
    EXPECT_GT(rejected, cases / 2);
  }
}

// Two random fields of two random nodes at once, 2,000 times.
TEST(TreeStreamCheck, AgreesWithTheConstructorOnRandomDoubleFaults) {
  const std::vector<Node> good = nodesOf(testing::unbalanced());
  const std::uint32_t n = static_cast<std::uint32_t>(good.size());
  std::mt19937 rng(7);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<Node> nodes = good;
    for (int m = 0; m < 2; ++m) {
      Node& node = nodes[rng() % n];
      const std::uint32_t value = rng() % (n + 2);
      switch (rng() % 5) {
        case 0: node.parent = value; break;
        case 1: node.first_child = value; break;
        case 2: node.num_children = value % 5; break;
        case 3: node.level = value % 5; break;
        default: node.word = value; break;
      }
    }
    EXPECT_EQ(streamed(3, 3, nodes, 5).passed(), constructorAccepts(3, 3, nodes))
        << "trial " << trial;
  }
}

// k = 2, L = 2: 0 -> {1, 2}, 1 -> {3, 4}; leaves 2, 3, 4. Node 2 made an
// inner node whose range is {3, 4} too: 3 and 4 still name 1 and lie in its
// range, one level down, and the words are 0..1 on the two leaves left;
// only the ranges' total (6 for 4 non-root nodes) shows that 3 and 4 lie in
// two ranges.
TEST(TreeStreamCheck, ARangeOverAnotherOwnersNodesIsCaughtByTheTotal) {
  std::vector<Node> nodes(5);
  nodes[0].first_child = 1;
  nodes[0].num_children = 2;
  nodes[1].level = 1;
  nodes[1].first_child = 3;
  nodes[1].num_children = 2;
  nodes[2].level = 1;
  nodes[2].first_child = 3;
  nodes[2].num_children = 2;
  nodes[3].parent = 1;
  nodes[3].level = 2;
  nodes[3].word = 0;
  nodes[4].parent = 1;
  nodes[4].level = 2;
  nodes[4].word = 1;
  EXPECT_FALSE(streamed(2, 2, nodes, 2).passed());
  EXPECT_FALSE(constructorAccepts(2, 2, nodes));
  nodes[2].num_children = 0;  // a leaf again, with the next word
  nodes[2].word = 2;
  EXPECT_TRUE(streamed(2, 2, nodes, 2).passed());
}

TEST(TreeStreamCheck, ChunksOutOfOrderOrMissingFail) {
  const std::vector<Node> good = nodesOf(testing::makeSyntheticVocabulary(3, 3, 5));
  const Vocabulary::NodeArray array(good.begin(), good.end());
  TreeStreamCheck skipped(3, 3, array.size());
  skipped.consume(array, 0, 10);
  skipped.consume(array, 20, array.size());
  EXPECT_FALSE(skipped.passed());
  TreeStreamCheck unfinished(3, 3, array.size());
  unfinished.consume(array, 0, array.size() - 1);
  EXPECT_FALSE(unfinished.passed());
}

// A .bowgvoc whose node 5 names another parent, checksum resealed: the
// loader's stream check fails and the constructor's check names the fault.
TEST(TreeStreamCheck, TheLoaderStillNamesTheFault) {
  const Vocabulary v = testing::makeSyntheticVocabulary(3, 3, 5);
  const std::string path = testing::outPath("stream_check.bowgvoc");
  saveVocabulary(v, path, VocabularyFormat::kBowg);
  std::string bytes = testing::readAll(path);
  const std::uint32_t other = v.nodes()[5].parent + 1;
  // Node i's record starts at 48 + 64 i; its parent is the first word.
  for (int b = 0; b < 4; ++b) bytes[48 + 64 * 5 + b] = static_cast<char>((other >> (8 * b)) & 0xff);
  testing::resealChecksum(&bytes);
  testing::writeAll(path, bytes);
  try {
    loadVocabulary(path);
    ADD_FAILURE() << "a node naming the wrong parent was accepted";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("names " + std::to_string(other) + " as its parent"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace bowg
