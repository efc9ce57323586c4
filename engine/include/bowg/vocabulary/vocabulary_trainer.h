// Offline training of the word vocabulary tree (paper Sec. III-A: k-medians
// with k-means++ seeding, DBoW2 layout, k_w = 10, L_w = 6): hierarchical
// k-medians for binary descriptors as in DBoW2's
// TemplatedVocabulary::create (Galvez-Lopez & Tardos, T-RO 2012, Sec. III).
//
// This is the source-independent part: it takes the descriptor sets of the
// training images, whatever produced them (image folders, rosbags).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/vocabulary/bow_vector.h"
#include "bowg/vocabulary/vocabulary.h"

namespace bowg {

struct TrainingOptions {
  /// k: branching factor (children per node), in [2, 1000] (what every
  /// vocabulary format loads). Paper: 10.
  int k = 10;
  /// L: depth of the tree (levels below the root), >= 1. Paper: 6.
  int L = 6;
  /// Weighting stored in the vocabulary. TF-IDF and IDF store the IDF weight
  /// log(N / N_w) per word (N images, N_w images containing word w; words
  /// no training image reached get 0); TF and BINARY store 1 (as DBoW2).
  WeightingType weighting = WeightingType::kTfIdf;
  /// Default scoring of the vocabulary (may be changed at run time).
  ScoringType scoring = ScoringType::kL1;
  /// Cap on the k-medians iterations of each clustering (>= 1). Each
  /// clustering stops earlier when no assignment changes.
  int max_iterations = 10;
  /// Seed of the k-means++ seeding (std::mt19937): same descriptors + same
  /// options = bit-identical vocabulary, whatever the thread count.
  std::uint32_t seed = 0;
  /// Worker threads (1..64); the result does not depend on it.
  int threads = 2;

  void validate() const;  ///< throws InvalidParameter naming the field
};

/// Progress: fraction of the work done in [0, 1] and a short stage name.
using TrainingProgress = std::function<void(double fraction, const std::string& stage)>;

/// Trains a vocabulary from the descriptors of each training image (one
/// vector per image; images may be empty but count in N for the IDF).
/// Throws InvalidParameter for bad options and std::invalid_argument when
/// there is no descriptor at all or more than 2^31.
///
/// Clustering of a node's descriptors: if there are at most k, each becomes
/// its own child (DBoW2); otherwise k-means++ seeding (probability of a
/// descriptor proportional to its squared Hamming distance to the nearest
/// chosen centre; fewer than k centres when fewer distinct descriptors
/// exist), then k-medians iterations: assign to the nearest centre (ties:
/// lowest index), centre = bitwise majority of its members (bit set when at
/// least half of them have it, DBoW2's rule). A node becomes a leaf at depth
/// L, or when it holds one descriptor or only identical ones. Nodes are
/// numbered breadth-first, words in leaf order.
Vocabulary trainVocabulary(const std::vector<std::vector<Descriptor>>& per_image,
                           const TrainingOptions& options,
                           const TrainingProgress& progress = TrainingProgress());

}  // namespace bowg
