#include "vocabulary/tree_stream_check.h"

#include <cmath>

namespace bowg {

TreeStreamCheck::TreeStreamCheck(int k, int L, std::size_t n)
    : k_(static_cast<std::uint32_t>(k < 0 ? 0 : k)),
      L_(static_cast<std::uint32_t>(L < 0 ? 0 : L)),
      n_(n),
      failed_(k < 2 || L < 1 || n < 2) {}

void TreeStreamCheck::consume(const Vocabulary::NodeArray& nodes, std::size_t begin,
                              std::size_t end) {
  if (failed_ || begin != checked_ || end > nodes.size() || end > n_) {
    failed_ = true;
    return;
  }
  for (std::size_t i = begin; i < end; ++i) {
    if (!check(nodes, i)) {
      failed_ = true;
      return;
    }
  }
  checked_ = end;
}

bool TreeStreamCheck::check(const Vocabulary::NodeArray& nodes, std::size_t i) {
  const Vocabulary::Node& node = nodes[i];
  if (!std::isfinite(node.weight) || node.weight < 0.0 || node.level > L_) return false;
  // The root's own fields are checkHeader's, which both constructors run.
  if (i != 0) {
    // The parent was checked before: its range lies after it and inside
    // the tree.
    const NodeId p = node.parent;
    if (p >= i) return false;
    const Vocabulary::Node& parent = nodes[p];
    if (parent.num_children == 0 || i < parent.first_child ||
        i - parent.first_child >= parent.num_children || node.level != parent.level + 1) {
      return false;
    }
  }
  if (node.num_children == 0) {
    if (i == 0) return false;
    ++leaves_;
    const WordId w = node.word;
    if (w == Vocabulary::kNoWord || w >= n_) return false;
    if (w >= word_to_node_.size()) word_to_node_.resize(w + 1, Vocabulary::kNoWord);
    if (word_to_node_[w] != Vocabulary::kNoWord) return false;  // on two leaves
    word_to_node_[w] = static_cast<NodeId>(i);
    return true;
  }
  if (node.num_children > k_ || node.first_child <= i ||
      static_cast<std::uint64_t>(node.first_child) + node.num_children > n_ ||
      node.word != Vocabulary::kNoWord) {
    return false;
  }
  range_total_ += node.num_children;
  return true;
}

bool TreeStreamCheck::passed() const {
  // Every non-root node lies in its parent's range; ranges of n - 1 nodes in
  // all cover each exactly once. W distinct words below W: 0..W-1.
  return !failed_ && checked_ == n_ && range_total_ == n_ - 1 &&
         word_to_node_.size() == leaves_;
}

}  // namespace bowg
