#include "bowg/database/packed_words.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "bowg/core/heap_bytes.h"

namespace bowg {

PackedWords::PackedWords(const std::vector<WordId>& words) {
  if (words.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("PackedWords: too many words");
  }
  size_ = static_cast<std::uint32_t>(words.size());
  if (words.empty()) return;
  const WordId largest = *std::max_element(words.begin(), words.end());
  width_ = 1;
  while (width_ < 4 && (largest >> (8 * width_)) != 0) ++width_;
  bytes_.resize(words.size() * width_);
  std::uint8_t* out = bytes_.data();
  for (WordId w : words) {
    for (int b = 0; b < width_; ++b) *out++ = static_cast<std::uint8_t>(w >> (8 * b));
  }
}

WordId PackedWords::operator[](std::size_t i) const {
  const std::uint8_t* in = bytes_.data() + i * width_;
  WordId w = 0;
  for (int b = 0; b < width_; ++b) w |= static_cast<WordId>(in[b]) << (8 * b);
  return w;
}

namespace {

// Little-endian ids of `Width` bytes; the width is a template argument so
// that each loop is a few loads and shifts per id.
template <int Width>
void unpackIds(const std::uint8_t* in, std::size_t n, WordId* out) {
  for (std::size_t i = 0; i < n; ++i, in += Width) {
    WordId w = 0;
    for (int b = 0; b < Width; ++b) w |= static_cast<WordId>(in[b]) << (8 * b);
    out[i] = w;
  }
}

}  // namespace

void PackedWords::unpack(std::vector<WordId>* out) const {
  out->resize(size_);
  switch (width_) {
    case 1:
      unpackIds<1>(bytes_.data(), size_, out->data());
      break;
    case 2:
      unpackIds<2>(bytes_.data(), size_, out->data());
      break;
    case 3:
      unpackIds<3>(bytes_.data(), size_, out->data());
      break;
    case 4:
      unpackIds<4>(bytes_.data(), size_, out->data());
      break;
    default:
      break;  // empty
  }
}

std::vector<WordId> PackedWords::unpack() const {
  std::vector<WordId> out;
  unpack(&out);
  return out;
}

std::size_t PackedWords::heapBytes() const { return vectorHeapBytes(bytes_); }

}  // namespace bowg
