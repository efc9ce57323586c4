// Synthetic vocabularies for tests and benchmarks: a full k-ary tree of depth
// L with random descriptors, built directly in the Vocabulary layout without
// k-medians training (a k=10 L=6 tree takes well under a second).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "bowg/vocabulary/vocabulary.h"

namespace bowg {
namespace testing {

inline Descriptor randomDescriptor(std::mt19937_64& rng) {
  Descriptor d;
  for (auto& b : d.bits) b = rng();
  return d;
}

inline std::vector<Descriptor> randomDescriptors(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Descriptor> out(n);
  for (auto& d : out) d = randomDescriptor(rng);
  return out;
}

/// A full tree: every inner node has k children, every leaf is at depth L.
/// Nodes in breadth-first order, words numbered in leaf order, leaf weights
/// uniform in [0.5, 5) (IDF-like), inner weights 0.
inline Vocabulary makeSyntheticVocabulary(int k, int L, std::uint64_t seed = 1,
                                          WeightingType weighting = WeightingType::kTfIdf,
                                          ScoringType scoring = ScoringType::kL1) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> weight(0.5, 5.0);
  std::vector<Vocabulary::Node> nodes(1);
  nodes.reserve(static_cast<std::size_t>((std::pow(k, L + 1) - 1) / (k - 1)));
  WordId next_word = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (static_cast<int>(nodes[i].level) == L) {
      nodes[i].word = next_word++;
      nodes[i].weight = weight(rng);
      continue;
    }
    nodes[i].first_child = static_cast<std::uint32_t>(nodes.size());
    nodes[i].num_children = static_cast<std::uint32_t>(k);
    const std::uint32_t level = nodes[i].level + 1;
    for (int c = 0; c < k; ++c) {
      Vocabulary::Node child;
      child.parent = static_cast<NodeId>(i);
      child.level = level;
      child.descriptor = randomDescriptor(rng);
      nodes.push_back(child);
    }
  }
  return Vocabulary(k, L, weighting, scoring, std::move(nodes));
}

}  // namespace testing
}  // namespace bowg
