// The offline-trained word vocabulary tree (paper Sec. III-A "Word Vocabulary
// Tree"; DBoW2 layout): a k-ary tree of binary descriptors whose leaves are the
// visual words, each with an IDF weight.
//
// Storage follows fbow's lesson: all nodes live in one contiguous array with
// the children of a node stored consecutively, so a descent touches k
// consecutive descriptors per level and a load is a single read.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bowg/core/huge_page_allocator.h"
#include "bowg/core/types.h"
#include "bowg/vocabulary/bow_vector.h"

namespace bowg {

/// The largest branching factor k and depth L that every vocabulary file
/// format's loader accepts; the writers and the trainer refuse more, so that
/// nothing they make is unloadable.
constexpr int kMaxBranching = 1000;
constexpr int kMaxDepth = 100;

class Vocabulary {
 public:
  static constexpr WordId kNoWord = 0xffffffffu;

  /// One tree node. Node 0 is the root (no descriptor, no word). Children of
  /// a node are the nodes [first_child, first_child + num_children).
  struct Node {
    NodeId parent = 0;
    std::uint32_t first_child = 0;
    std::uint32_t num_children = 0;
    std::uint32_t level = 0;  ///< depth: root 0, its children 1, ...
    WordId word = kNoWord;    ///< set for leaves only
    double weight = 0.0;      ///< IDF weight (leaves); 0 for inner nodes
    Descriptor descriptor;
  };

  /// The node array: one block, in huge pages where it is large (a k=10
  /// L=6 tree is 71 MB; huge_page_allocator.h).
  using NodeArray = std::vector<Node, HugePageAllocator<Node>>;

  Vocabulary() = default;

  /// Builds from nodes in the layout above; validates the structure
  /// (parents, child ranges, words 0..W-1 each on exactly one leaf) and
  /// throws FormatError naming the first inconsistency.
  Vocabulary(int branching, int depth, WeightingType weighting, ScoringType scoring,
             NodeArray nodes);
  /// Same, from a plain vector (copied into a NodeArray).
  Vocabulary(int branching, int depth, WeightingType weighting, ScoringType scoring,
             const std::vector<Node>& nodes);

  bool empty() const { return nodes_.size() <= 1; }
  int branching() const { return k_; }  ///< k
  int depth() const { return L_; }      ///< L
  std::size_t wordCount() const { return word_to_node_.size(); }
  std::size_t nodeCount() const { return nodes_.size(); }
  WeightingType weighting() const { return weighting_; }
  ScoringType scoring() const { return scoring_; }
  const NodeArray& nodes() const { return nodes_; }
  NodeId nodeOfWord(WordId w) const { return word_to_node_[w]; }
  double wordWeight(WordId w) const { return word_weights_[w]; }

  /// Descends to a leaf by minimum Hamming distance (ties: lowest index).
  /// If `node_at_level` is given, it receives the ancestor of the leaf at
  /// depth `level` (1..L), or the leaf itself when the leaf is shallower.
  WordId transform(const Descriptor& d, NodeId* node_at_level = nullptr, int level = 0) const;

  /// Transforms all descriptors of one image:
  ///  - `bow`: weighted histogram (weighting scheme of the vocabulary),
  ///    normalised for its scoring type;
  ///  - `direct`: optional direct index at depth `direct_level`;
  ///  - `words`: optional word of each descriptor (index-aligned).
  void transform(const std::vector<Descriptor>& descriptors, BowVector* bow,
                 DirectIndex* direct = nullptr, int direct_level = 0,
                 std::vector<WordId>* words = nullptr) const;

  /// The `bow` that transform() gives for an image whose features have these
  /// words (bit for bit: the same weighting and normalisation), so that a
  /// database can keep words and rebuild vectors on demand. Throws
  /// std::out_of_range for a word id >= wordCount().
  BowVector bowFromWords(const std::vector<WordId>& words) const;

  /// 64-bit content hash over k, L, the weighting scheme and every node (not
  /// the scoring type, which is a run-time choice); databases record it so
  /// they are never loaded against another vocabulary.
  std::uint64_t fingerprint() const { return fingerprint_; }

  /// Replace the scoring type: it is a property of how vectors are compared,
  /// not of the tree, so users may choose it per run.
  void setScoring(ScoringType s) { scoring_ = s; }

 private:
  /// transform()'s weighting and normalisation over the image's
  /// (word, feature) pairs sorted by word.
  void weighSortedWords(const std::vector<std::pair<WordId, std::uint32_t>>& word_of,
                        BowVector* bow) const;
  // The .bowgvoc loader hashes its node block once for its file checksum
  // and the fingerprint together, and checks the tree chunk by chunk
  // (engine/src/vocabulary/vocabulary_records.h).
  friend struct VocabularyRecords;
  Vocabulary(int branching, int depth, WeightingType weighting, ScoringType scoring,
             NodeArray nodes, std::uint64_t fingerprint);
  /// A tree that passed TreeStreamCheck, with its word -> leaf table.
  Vocabulary(int branching, int depth, WeightingType weighting, ScoringType scoring,
             NodeArray nodes, std::uint64_t fingerprint, std::vector<NodeId> word_to_node);

  void index();         // validates, builds word_to_node_ (and word_weights_)
  void indexWeights();  // word_weights_ from word_to_node_ and the nodes

  int k_ = 0;
  int L_ = 0;
  WeightingType weighting_ = WeightingType::kTfIdf;
  ScoringType scoring_ = ScoringType::kL1;
  NodeArray nodes_;
  std::vector<NodeId> word_to_node_;
  /// Each word's weight (its leaf's), in word order: weighing an image's
  /// words reads one compact array instead of the word's leaf among the
  /// tree's nodes (two cache misses a word on a large tree: a tenth of a
  /// large database file's load, which weighs every stored keyframe).
  std::vector<double> word_weights_;
  std::uint64_t fingerprint_ = 0;
};

}  // namespace bowg
