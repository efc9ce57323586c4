// The vocabulary tree: validation of the node layout, the descent and the
// image transform (paper Sec. III-A; weighting as DBoW2's
// TemplatedVocabulary::transform).
#include "bowg/vocabulary/vocabulary.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "bowg/core/checksum.h"
#include "bowg/core/errors.h"
#include "bowg/core/id_index_sort.h"
#include "vocabulary/tree_descent.h"
#include "vocabulary/vocabulary_records.h"

namespace bowg {

// C++14 needs an out-of-class definition for odr-used static constexpr members.
constexpr WordId Vocabulary::kNoWord;

namespace {

using Node = Vocabulary::Node;
constexpr WordId kNoWord = Vocabulary::kNoWord;

std::string nodeName(std::size_t i) { return "node " + std::to_string(i); }

inline void putLe(unsigned char* out, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out[i] = static_cast<unsigned char>(v >> (8 * i));
}

void encodeRecord(const Vocabulary::Node& n, unsigned char out[64]) {
  putLe(out + 0, n.parent, 4);
  putLe(out + 4, n.first_child, 4);
  putLe(out + 8, n.num_children, 4);
  putLe(out + 12, n.level, 4);
  putLe(out + 16, n.word, 4);
  putLe(out + 20, 0, 4);
  std::uint64_t weight_bits;
  std::memcpy(&weight_bits, &n.weight, sizeof(weight_bits));
  putLe(out + 24, weight_bits, 8);
  for (int b = 0; b < 4; ++b) putLe(out + 32 + 8 * b, n.descriptor.bits[b], 8);
}

// k, L, the weighting and scoring types, the node count and the root.
void checkHeader(int k, int L, WeightingType weighting, ScoringType scoring,
                 const Vocabulary::NodeArray& nodes) {
  const int w = static_cast<int>(weighting);
  const int s = static_cast<int>(scoring);
  if (k < 2) throw FormatError("vocabulary: branching factor k = " + std::to_string(k) + " < 2");
  if (L < 1) throw FormatError("vocabulary: depth L = " + std::to_string(L) + " < 1");
  if (w < 0 || w > 3) throw FormatError("vocabulary: unknown weighting type " + std::to_string(w));
  if (s < 0 || s > 5) throw FormatError("vocabulary: unknown scoring type " + std::to_string(s));
  const std::size_t n = nodes.size();
  if (n < 2) throw FormatError("vocabulary: no node below the root");
  if (n >= kNoWord) throw FormatError("vocabulary: too many nodes (" + std::to_string(n) + ")");

  const Node& root = nodes[0];
  if (root.level != 0)
    throw FormatError("vocabulary: root has level " + std::to_string(root.level));
  if (root.word != kNoWord)
    throw FormatError("vocabulary: root carries word " + std::to_string(root.word));
  if (root.num_children == 0) throw FormatError("vocabulary: root has no children");
}

// The tree's shape: weights, levels, child ranges and parents. Returns the
// number of leaves.
std::size_t checkTree(int k, int L, const Vocabulary::NodeArray& nodes) {
  const std::size_t n = nodes.size();
  // Every non-root node must be claimed by exactly one child range: its
  // parent's. Because a child must name the range's owner as its parent,
  // two ranges can never claim the same node; `claimed` catches orphans.
  // Child ranges start after their owner, so the parent relation is acyclic
  // and a descent always ends.
  std::vector<char> claimed(n, 0);
  std::size_t leaves = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Node& node = nodes[i];
    // Weights are IDF values (log N / N_i) or 1 (TF): never negative. A
    // negative one would make eq. 1's vectors and every score meaningless.
    if (!std::isfinite(node.weight))
      throw FormatError("vocabulary: " + nodeName(i) + " has a non-finite weight");
    if (node.weight < 0.0) {
      throw FormatError("vocabulary: " + nodeName(i) + " has a negative weight (" +
                        formatNumber(node.weight) + ")");
    }
    if (node.level > static_cast<std::uint32_t>(L)) {
      throw FormatError("vocabulary: " + nodeName(i) + " is at level " +
                        std::to_string(node.level) + ", deeper than L = " + std::to_string(L));
    }
    if (node.num_children == 0) {
      if (i != 0) ++leaves;
      continue;
    }
    if (node.num_children > static_cast<std::uint32_t>(k)) {
      throw FormatError("vocabulary: " + nodeName(i) + " has " + std::to_string(node.num_children) +
                        " children, more than k = " + std::to_string(k));
    }
    if (node.first_child <= i) {
      throw FormatError("vocabulary: " + nodeName(i) + " has its children at " +
                        std::to_string(node.first_child) + ", not after itself (cycle)");
    }
    if (static_cast<std::uint64_t>(node.first_child) + node.num_children > n) {
      throw FormatError(
          "vocabulary: child range [" + std::to_string(node.first_child) + ", " +
          std::to_string(static_cast<std::uint64_t>(node.first_child) + node.num_children) +
          ") of " + nodeName(i) + " is out of bounds (" + std::to_string(n) + " nodes)");
    }
    if (node.word != kNoWord) {
      throw FormatError("vocabulary: inner " + nodeName(i) + " carries word " +
                        std::to_string(node.word));
    }
    for (std::uint32_t c = node.first_child; c < node.first_child + node.num_children; ++c) {
      const Node& child = nodes[c];
      if (child.parent != i) {
        throw FormatError("vocabulary: " + nodeName(c) + " lies in the child range of " +
                          nodeName(i) + " but names " + std::to_string(child.parent) +
                          " as its parent");
      }
      if (child.level != node.level + 1) {
        throw FormatError("vocabulary: " + nodeName(c) + " has level " +
                          std::to_string(child.level) + " but its parent " + std::to_string(i) +
                          " has level " + std::to_string(node.level));
      }
      claimed[c] = 1;
    }
  }
  for (std::size_t i = 1; i < n; ++i) {
    if (!claimed[i]) {
      throw FormatError("vocabulary: " + nodeName(i) + " is in no child range (bad parent " +
                        std::to_string(nodes[i].parent) + ")");
    }
  }

  return leaves;
}

// Words 0..W-1, each on exactly one leaf: the word -> leaf table.
std::vector<NodeId> wordsToNodes(const Vocabulary::NodeArray& nodes, std::size_t leaves) {
  const std::size_t n = nodes.size();
  std::vector<NodeId> word_to_node(leaves, kNoWord);
  // Words: 0..W-1, each on exactly one leaf, W = number of leaves.
  for (std::size_t i = 1; i < n; ++i) {
    const Node& node = nodes[i];
    if (node.num_children != 0) continue;
    if (node.word == kNoWord) throw FormatError("vocabulary: leaf " + nodeName(i) + " has no word");
    if (node.word >= leaves) {
      throw FormatError("vocabulary: leaf " + nodeName(i) + " has word id " +
                        std::to_string(node.word) + " but there are only " +
                        std::to_string(leaves) + " leaves (ids must be 0..W-1)");
    }
    if (word_to_node[node.word] != kNoWord) {
      throw FormatError("vocabulary: word " + std::to_string(node.word) + " is on both " +
                        nodeName(word_to_node[node.word]) + " and " + nodeName(i));
    }
    word_to_node[node.word] = static_cast<NodeId>(i);
  }

  return word_to_node;
}

// Fingerprint: every field that changes what transform() returns, plus the
// weighting; not the scoring type (a run-time choice, setScoring()).
std::uint64_t fingerprintOf(int k, int L, WeightingType weighting,
                            const Vocabulary::NodeArray& nodes) {
  Checksum64 h = VocabularyRecords::fingerprintStart(k, L, weighting, nodes.size());
  // Each node is hashed as one 64-byte little-endian record (the .bowgvoc
  // record layout), which keeps the checksum on its word-wise fast path.
  unsigned char record[64];
  for (const Node& node : nodes) {
    encodeRecord(node, record);
    h.update(record, sizeof(record));
  }
  return h.value();
}

// The BoW value of a word seen `count` times among the image's features
// (inv_n = 1 / their number), with the word's weight `idf`.
double wordValue(WeightingType weighting, double count, double inv_n, double idf) {
  switch (weighting) {
    case WeightingType::kTfIdf:
      return count * inv_n * idf;
    case WeightingType::kTf:
      return count * inv_n;
    case WeightingType::kIdf:
      return idf;
    case WeightingType::kBinary:
      return 1.0;
  }
  return 0.0;
}

}  // namespace

Vocabulary::Vocabulary(int branching, int depth, WeightingType weighting, ScoringType scoring,
                       NodeArray nodes)
    : k_(branching), L_(depth), weighting_(weighting), scoring_(scoring), nodes_(std::move(nodes)) {
  index();
  fingerprint_ = fingerprintOf(k_, L_, weighting_, nodes_);
}

Vocabulary::Vocabulary(int branching, int depth, WeightingType weighting, ScoringType scoring,
                       const std::vector<Node>& nodes)
    : Vocabulary(branching, depth, weighting, scoring, NodeArray(nodes.begin(), nodes.end())) {}

Vocabulary::Vocabulary(int branching, int depth, WeightingType weighting, ScoringType scoring,
                       NodeArray nodes, std::uint64_t fingerprint)
    : k_(branching),
      L_(depth),
      weighting_(weighting),
      scoring_(scoring),
      nodes_(std::move(nodes)),
      fingerprint_(fingerprint) {
  index();
}

Vocabulary::Vocabulary(int branching, int depth, WeightingType weighting, ScoringType scoring,
                       NodeArray nodes, std::uint64_t fingerprint, std::vector<NodeId> word_to_node)
    : k_(branching),
      L_(depth),
      weighting_(weighting),
      scoring_(scoring),
      nodes_(std::move(nodes)),
      word_to_node_(std::move(word_to_node)),
      fingerprint_(fingerprint) {
  checkHeader(k_, L_, weighting_, scoring_, nodes_);
  indexWeights();
}

void Vocabulary::index() {
  checkHeader(k_, L_, weighting_, scoring_, nodes_);
  const std::size_t leaves = checkTree(k_, L_, nodes_);
  word_to_node_ = wordsToNodes(nodes_, leaves);
  indexWeights();
}

void Vocabulary::indexWeights() {
  word_weights_.resize(word_to_node_.size());
  for (std::size_t w = 0; w < word_to_node_.size(); ++w) {
    word_weights_[w] = nodes_[word_to_node_[w]].weight;
  }
}

// 40 header bytes (a multiple of 8, so the records stay word-aligned).
Checksum64 VocabularyRecords::fingerprintStart(int k, int L, WeightingType weighting,
                                               std::size_t nodes) {
  Checksum64 h;
  h.update("BOWGFP01", 8);
  h.updateU64(static_cast<std::uint64_t>(k));
  h.updateU64(static_cast<std::uint64_t>(L));
  h.updateU64(static_cast<std::uint64_t>(static_cast<int>(weighting)));
  h.updateU64(nodes);
  return h;
}

Vocabulary VocabularyRecords::build(int k, int L, WeightingType weighting, ScoringType scoring,
                                    Vocabulary::NodeArray nodes, std::uint64_t fingerprint) {
  return Vocabulary(k, L, weighting, scoring, std::move(nodes), fingerprint);
}

Vocabulary VocabularyRecords::buildChecked(int k, int L, WeightingType weighting,
                                           ScoringType scoring, Vocabulary::NodeArray nodes,
                                           std::uint64_t fingerprint, TreeStreamCheck* check) {
  if (!check->passed()) return build(k, L, weighting, scoring, std::move(nodes), fingerprint);
  return Vocabulary(k, L, weighting, scoring, std::move(nodes), fingerprint,
                    check->takeWordToNode());
}

WordId Vocabulary::transform(const Descriptor& d, NodeId* node_at_level, int level) const {
  if (nodes_.size() < 2) throw std::logic_error("Vocabulary::transform: the vocabulary is empty");
  if (node_at_level != nullptr && level < 1) {
    throw std::invalid_argument("Vocabulary::transform: level must be >= 1, got " +
                                std::to_string(level));
  }
  const Node* nodes = nodes_.data();
  std::uint32_t current = 0;
  NodeId at_level = 0;
  // Children are consecutive in the node array: the inner loop reads k
  // adjacent 64-byte records (one cache line each).
  while (nodes[current].num_children != 0) {
    const Node* child = nodes + nodes[current].first_child;
    const Node* end = child + nodes[current].num_children;
    std::uint32_t best = nodes[current].first_child;
    int best_distance = hammingDistance(d, child->descriptor);
    std::uint32_t index = best;
    for (++child, ++index; child != end; ++child, ++index) {
      const int distance = hammingDistance(d, child->descriptor);
      if (distance < best_distance) {
        best_distance = distance;
        best = index;
      }
    }
    current = best;
    if (static_cast<int>(nodes[current].level) <= level) at_level = current;
  }
  if (node_at_level != nullptr) *node_at_level = at_level;
  return nodes[current].word;
}

void Vocabulary::transform(const std::vector<Descriptor>& descriptors, BowVector* bow,
                           DirectIndex* direct, int direct_level,
                           std::vector<WordId>* words) const {
  if (bow == nullptr) throw std::invalid_argument("Vocabulary::transform: bow must not be null");
  if (direct != nullptr && direct_level < 1) {
    throw std::invalid_argument("Vocabulary::transform: direct_level must be >= 1, got " +
                                std::to_string(direct_level));
  }
  bow->clear();
  if (direct != nullptr) direct->clear();
  if (words != nullptr) words->clear();
  if (descriptors.empty()) return;
  const std::size_t n = descriptors.size();

  // Word of each descriptor (and node at the direct-index level), then one
  // sort: no allocation per descriptor, O(n) overall (sortIdIndexPairs).
  std::vector<std::pair<WordId, std::uint32_t>> word_of(n);
  std::vector<std::pair<NodeId, std::uint32_t>> node_of;
  if (direct != nullptr) node_of.resize(n);
  if (nodes_.size() < 2) throw std::logic_error("Vocabulary::transform: the vocabulary is empty");
  const std::size_t kBatch = tree_descent::kBatch;
  const tree_descent::DescendBatch descend = tree_descent::bestDescendBatch();
  for (std::size_t i = 0; i < n; i += kBatch) {
    const std::size_t count = std::min(kBatch, n - i);
    WordId w[kBatch];
    NodeId node[kBatch];
    descend(nodes_.data(), descriptors.data() + i, count, direct != nullptr ? direct_level : 0, w,
            node);
    for (std::size_t g = 0; g < count; ++g) {
      word_of[i + g] = {w[g], static_cast<std::uint32_t>(i + g)};
      if (direct != nullptr) node_of[i + g] = {node[g], static_cast<std::uint32_t>(i + g)};
    }
  }
  if (words != nullptr) {
    words->resize(n);
    for (std::size_t i = 0; i < n; ++i) (*words)[i] = word_of[i].first;
  }
  sortIdIndexPairs(&word_of);
  weighSortedWords(word_of, bow);

  if (direct != nullptr) {
    sortIdIndexPairs(&node_of);
    *direct = std::move(node_of);
  }
}

void Vocabulary::weighSortedWords(const std::vector<std::pair<WordId, std::uint32_t>>& word_of,
                                  BowVector* bow) const {
  const std::size_t n = word_of.size();
  // Weighting as DBoW2 (T-RO 2012, Sec. IV): with n_id occurrences of word
  // i in image d of n_d features and idf_i the word's weight,
  //   TF-IDF: (n_id / n_d) * idf_i,  TF: n_id / n_d,
  //   IDF:    idf_i (DBoW2 adds it once per present word, addIfNotExist),
  //   BINARY: 1.
  // Words of weight 0 are "stopped" (DBoW2's `if (w > 0)`). n_d counts all
  // features of the image.
  const double inv_n = 1.0 / static_cast<double>(n);
  bow->reserve(n);
  for (std::size_t i = 0; i < n;) {
    const WordId w = word_of[i].first;
    std::size_t j = i;
    while (j < n && word_of[j].first == w) ++j;
    const double value = wordValue(weighting_, static_cast<double>(j - i), inv_n, word_weights_[w]);
    if (value > 0.0) bow->emplace_back(w, value);
    i = j;
  }
  normaliseBowVector(scoring_, bow);
}

BowVector Vocabulary::bowFromWords(const std::vector<WordId>& words) const {
  BowVector bow;
  if (words.empty()) return bow;
  std::vector<std::pair<WordId, std::uint32_t>> word_of(words.size());
  for (std::uint32_t i = 0; i < words.size(); ++i) {
    if (words[i] >= word_to_node_.size())
      throw std::out_of_range("Vocabulary::bowFromWords: word id " + std::to_string(words[i]) +
                              " >= " + std::to_string(word_to_node_.size()));
    word_of[i] = {words[i], i};
  }
  sortIdIndexPairs(&word_of);
  weighSortedWords(word_of, &bow);
  return bow;
}

}  // namespace bowg
