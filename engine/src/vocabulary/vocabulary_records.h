// The .bowgvoc loader's one-pass path. Its node block is, byte for byte, the
// 64-byte records the vocabulary fingerprint hashes (little-endian host,
// reserved bytes zero), so the loader feeds the block to its file checksum
// and to the fingerprint together (updateBoth: a 71 MB block hashed twice
// for about the price of once) and hands the fingerprint over here.
// Not installed: private to the engine library.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bowg/core/checksum.h"
#include "bowg/vocabulary/vocabulary.h"
#include "vocabulary/tree_stream_check.h"

namespace bowg {

struct VocabularyRecords {
  /// The fingerprint's hash after its header (k, L, weighting, node count):
  /// the records follow.
  static Checksum64 fingerprintStart(int k, int L, WeightingType weighting, std::size_t nodes);

  /// Validates and indexes like Vocabulary's constructor (FormatError), with
  /// `fingerprint` = fingerprintStart(...) fed the records of `nodes`.
  static Vocabulary build(int k, int L, WeightingType weighting, ScoringType scoring,
                          Vocabulary::NodeArray nodes, std::uint64_t fingerprint);

  /// The same for a tree `check` has seen whole: when it passed, without
  /// checking the tree again; otherwise build(), whose checks name the
  /// fault.
  static Vocabulary buildChecked(int k, int L, WeightingType weighting, ScoringType scoring,
                                 Vocabulary::NodeArray nodes, std::uint64_t fingerprint,
                                 TreeStreamCheck* check);
};

}  // namespace bowg
