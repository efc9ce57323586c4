// The vocabulary tree's descent (paper Sec. III-A "Word Vocabulary Tree"):
// each descriptor goes, level by level, to the child nearest to it in
// Hamming distance (the first of equally near children), down to a leaf and
// its word. Two implementations giving the same nodes: a portable one, and
// one for x86-64 CPUs with AVX2 that computes a node's child distances in
// vector registers and picks the nearest without a branch per child (the
// portable loop's data-dependent branch mispredicts about twice a level).
#pragma once

#include <cstddef>
#include <cstdint>

#include "bowg/vocabulary/vocabulary.h"
#include "core/prefetch.h"

namespace bowg {
namespace tree_descent {

/// Descriptors descended in lockstep by one call.
constexpr std::size_t kBatch = 8;

/// Descends `count` (<= kBatch) descriptors `d` in lockstep from the root of
/// `nodes`: words[g] is the word of descriptor g's leaf, at_level[g] its
/// deepest node at a level <= `level` (0, the root, when level is 0).
/// Prefetches each descriptor's next child block before it is needed: the
/// deep levels of a k=10 L=6 tree (70 MB) miss the cache, and interleaving
/// the descents overlaps those misses.
using DescendBatch = void (*)(const Vocabulary::Node* nodes, const Descriptor* d, std::size_t count,
                              int level, WordId* words, NodeId* at_level);

void descendBatchPortable(const Vocabulary::Node* nodes, const Descriptor* d, std::size_t count,
                          int level, WordId* words, NodeId* at_level);

/// descendBatchPortable's results with AVX2. Call only where cpuHasAvx2()
/// (core/cpu_features.h); std::logic_error where this build has no AVX2 version
/// (other architectures).
void descendBatchAvx2(const Vocabulary::Node* nodes, const Descriptor* d, std::size_t count,
                      int level, WordId* words, NodeId* at_level);

/// Descriptor g's step to child `chosen` (both descents): its node, its
/// node at `level`, and the chosen node's child block prefetched.
inline void moveTo(const Vocabulary::Node* nodes, std::uint32_t chosen, int level,
                   std::uint32_t* current, NodeId* at_level) {
  *current = chosen;
  if (static_cast<int>(nodes[chosen].level) <= level) *at_level = chosen;
  const Vocabulary::Node& next = nodes[chosen];
  for (std::uint32_t c = 0; c < next.num_children; ++c) {
    prefetchRead(nodes + next.first_child + c);
  }
}

/// The fastest descent this CPU runs, chosen once.
DescendBatch bestDescendBatch();

}  // namespace tree_descent
}  // namespace bowg
