// The tree checks of Vocabulary's constructor (its child ranges, parents,
// levels, weights and words) made node by node, so that the .bowgvoc loader
// runs them on each chunk of the node block while it is still in the cache,
// instead of in two more passes over the 71 MB block after it. The same
// invariants, seen from the child's side: a non-root node's parent comes
// before it, holds it in its child range and is one level up; the child
// ranges add up to the n - 1 non-root nodes, so no node lies in two ranges
// and every range member names the range's owner; the leaves carry the
// words 0..W-1, once each. It only says whether the tree passed: on a
// failure the constructor's checks run and name the fault.
// Not installed: private to the engine library.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bowg/vocabulary/vocabulary.h"

namespace bowg {

class TreeStreamCheck {
 public:
  /// A tree of `n` nodes, branching factor `k`, depth `L`.
  TreeStreamCheck(int k, int L, std::size_t n);

  /// Checks nodes [begin, end) of `nodes`; those before `begin` were
  /// checked by earlier calls. Stops checking after the first fault.
  void consume(const Vocabulary::NodeArray& nodes, std::size_t begin, std::size_t end);

  /// After all n nodes: whether the tree passed every check.
  bool passed() const;

  /// The word -> leaf table of a tree that passed.
  std::vector<NodeId> takeWordToNode() { return std::move(word_to_node_); }

 private:
  bool check(const Vocabulary::NodeArray& nodes, std::size_t i);

  std::uint32_t k_, L_;
  std::size_t n_;
  std::size_t checked_ = 0;
  std::uint64_t range_total_ = 0;  // sum of the child ranges' sizes
  std::size_t leaves_ = 0;
  bool failed_ = false;
  std::vector<NodeId> word_to_node_;
};

}  // namespace bowg
