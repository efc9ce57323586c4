// The portable tree descent and the choice between it and the AVX2 one
// (tree_descent.h).
#include "vocabulary/tree_descent.h"

#include "core/cpu_features.h"

namespace bowg {
namespace tree_descent {

void descendBatchPortable(const Vocabulary::Node* nodes, const Descriptor* d, std::size_t count,
                          int level, WordId* words, NodeId* at_level) {
  std::uint32_t current[kBatch];
  for (std::size_t g = 0; g < count; ++g) {
    current[g] = 0;
    at_level[g] = 0;
  }
  for (bool moved = true; moved;) {
    moved = false;
    for (std::size_t g = 0; g < count; ++g) {
      const Vocabulary::Node& node = nodes[current[g]];
      if (node.num_children == 0) continue;
      const Vocabulary::Node* child = nodes + node.first_child;
      std::uint32_t best = node.first_child;
      int best_distance = hammingDistance(d[g], child->descriptor);
      for (std::uint32_t c = 1; c < node.num_children; ++c) {
        const int distance = hammingDistance(d[g], child[c].descriptor);
        if (distance < best_distance) {
          best_distance = distance;
          best = node.first_child + c;
        }
      }
      moveTo(nodes, best, level, &current[g], &at_level[g]);
      moved = true;
    }
  }
  for (std::size_t g = 0; g < count; ++g) words[g] = nodes[current[g]].word;
}

DescendBatch bestDescendBatch() {
  static const DescendBatch best = cpuHasAvx2() ? descendBatchAvx2 : descendBatchPortable;
  return best;
}

}  // namespace tree_descent
}  // namespace bowg
