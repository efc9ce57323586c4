#include "bowg/core/checksum.h"

#include <cstring>

#include "core/little_endian.h"

namespace bowg {
namespace {

const std::uint64_t kFnvPrime = 0x100000001b3ull;

inline std::uint64_t mixWord(std::uint64_t h, std::uint64_t w) { return (h ^ w) * kFnvPrime; }

}  // namespace

void Checksum64::update(const void* data, std::size_t size) {
  const unsigned char* p = static_cast<const unsigned char*>(data);
  length_ += size;
  // Complete a partially filled word first.
  while (pending_bytes_ != 0 && size > 0) {
    pending_ |= static_cast<std::uint64_t>(*p++) << (8 * pending_bytes_);
    --size;
    if (++pending_bytes_ == 8) {
      hash_ = mixWord(hash_, pending_);
      pending_ = 0;
      pending_bytes_ = 0;
    }
  }
  std::uint64_t h = hash_;
  while (size >= 8) {
    h = mixWord(h, loadLittleEndian<std::uint64_t>(p));
    p += 8;
    size -= 8;
  }
  hash_ = h;
  while (size > 0) {
    pending_ |= static_cast<std::uint64_t>(*p++) << (8 * pending_bytes_);
    ++pending_bytes_;
    --size;
  }
}

void updateBoth(Checksum64* a, Checksum64* b, const void* data, std::size_t size) {
  if (a->pending_bytes_ != 0 || b->pending_bytes_ != 0) {
    a->update(data, size);
    b->update(data, size);
    return;
  }
  // Both at a word boundary: the word loops run side by side.
  const unsigned char* p = static_cast<const unsigned char*>(data);
  const std::size_t words = size / 8;
  std::uint64_t ha = a->hash_, hb = b->hash_;
  for (std::size_t i = 0; i < words; ++i, p += 8) {
    const std::uint64_t w = loadLittleEndian<std::uint64_t>(p);
    ha = mixWord(ha, w);
    hb = mixWord(hb, w);
  }
  a->hash_ = ha;
  b->hash_ = hb;
  a->length_ += words * 8;
  b->length_ += words * 8;
  const std::size_t tail = size - words * 8;
  a->update(p, tail);
  b->update(p, tail);
}

void Checksum64::updateU32(std::uint32_t v) {
  unsigned char b[4];
  for (int i = 0; i < 4; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
  update(b, 4);
}

void Checksum64::updateU64(std::uint64_t v) {
  unsigned char b[8];
  for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
  update(b, 8);
}

void Checksum64::updateDouble(double v) {
  std::uint64_t bits;
  static_assert(sizeof(bits) == sizeof(v), "double must be 64-bit");
  std::memcpy(&bits, &v, sizeof(bits));
  updateU64(bits);
}

std::uint64_t Checksum64::value() const {
  std::uint64_t h = hash_;
  // The tail is tagged with its byte count so that "ab" and "ab\0" differ.
  if (pending_bytes_ != 0)
    h = mixWord(h, pending_ ^ (static_cast<std::uint64_t>(pending_bytes_) << 56));
  h = mixWord(h, length_);
  // Final avalanche (MurmurHash3's fmix64) so that every input bit reaches
  // every output bit.
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ull;
  h ^= h >> 33;
  return h;
}

std::uint64_t checksum64(const void* data, std::size_t size) {
  Checksum64 c;
  c.update(data, size);
  return c.value();
}

}  // namespace bowg
