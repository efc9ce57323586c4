// A database entry's word ids in as few bytes each as its largest id needs:
// 2 with a vocabulary of up to 65,536 words (the bundled k=10 L=4 one), 3 up
// to 16.7 M (k=10 L=6 has 1 M), 4 beyond. The ids are kept exactly; they
// are read back when the entry's BoW vector, raw groups or direct index are
// rebuilt (Database::bow(), rawGroups(), directIndexFromWords).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

class PackedWords {
 public:
  PackedWords() = default;
  explicit PackedWords(const std::vector<WordId>& words);

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  /// Bytes per id: those of the largest id (at least 1; 0 when empty).
  int bytesPerWord() const { return width_; }

  WordId operator[](std::size_t i) const;
  /// Every id, in order, into `out` (resized; its capacity is reused).
  void unpack(std::vector<WordId>* out) const;
  std::vector<WordId> unpack() const;

  /// Heap bytes held (the block's capacity).
  std::size_t heapBytes() const;

 private:
  std::vector<std::uint8_t> bytes_;  ///< little-endian ids, width_ bytes each
  std::uint32_t size_ = 0;
  std::uint8_t width_ = 0;
};

}  // namespace bowg
