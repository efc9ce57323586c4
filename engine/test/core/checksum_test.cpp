// checksum64: split invariance, sensitivity to every bit and to the length,
// and agreement with an independent transcription of its definition.
#include "bowg/core/checksum.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace bowg {
namespace {

// The definition in checksum.h, written out independently: FNV-1a over
// little-endian 64-bit words, tail word tagged with its byte count,
// length mixed in, MurmurHash3 fmix64.
std::uint64_t reference(const std::string& s) {
  const std::uint64_t prime = 0x100000001b3ull;
  std::uint64_t h = 0xcbf29ce484222325ull;
  std::size_t i = 0;
  for (; i + 8 <= s.size(); i += 8) {
    std::uint64_t w = 0;
    for (int b = 0; b < 8; ++b)
      w |= static_cast<std::uint64_t>(static_cast<unsigned char>(s[i + b])) << (8 * b);
    h = (h ^ w) * prime;
  }
  if (i < s.size()) {
    std::uint64_t w = 0;
    for (std::size_t b = 0; i + b < s.size(); ++b) {
      w |= static_cast<std::uint64_t>(static_cast<unsigned char>(s[i + b])) << (8 * b);
    }
    w ^= static_cast<std::uint64_t>(s.size() - i) << 56;
    h = (h ^ w) * prime;
  }
  h = (h ^ s.size()) * prime;
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ull;
  h ^= h >> 33;
  return h;
}

TEST(Checksum64, MatchesTheDefinition) {
  for (const std::string s : {std::string(), std::string("a"), std::string("abcdefgh"),
                              std::string("abcdefghi"), std::string(1000, '\x7f')}) {
    EXPECT_EQ(checksum64(s.data(), s.size()), reference(s)) << s.size();
  }
}

TEST(Checksum64, AnySplitGivesTheSameValue) {
  std::string s;
  for (int i = 0; i < 100; ++i) s.push_back(static_cast<char>(i * 37));
  const std::uint64_t whole = checksum64(s.data(), s.size());
  for (std::size_t a = 0; a <= s.size(); a += 7) {
    for (std::size_t b = a; b <= s.size(); b += 11) {
      Checksum64 c;
      c.update(s.data(), a);
      c.update(s.data() + a, b - a);
      c.update(s.data() + b, s.size() - b);
      EXPECT_EQ(c.value(), whole);
    }
  }
}

TEST(Checksum64, EverySingleBitFlipChangesTheValue) {
  std::string s(64, '\0');
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = static_cast<char>(i);
  const std::uint64_t base = checksum64(s.data(), s.size());
  for (std::size_t bit = 0; bit < s.size() * 8; ++bit) {
    std::string t = s;
    t[bit / 8] = static_cast<char>(t[bit / 8] ^ (1 << (bit % 8)));
    EXPECT_NE(checksum64(t.data(), t.size()), base) << bit;
  }
}

TEST(Checksum64, TrailingZerosAndTruncationChangeTheValue) {
  const std::string a("ab"), b("ab\0", 3), c(16, '\0'), d(8, '\0');
  EXPECT_NE(checksum64(a.data(), a.size()), checksum64(b.data(), b.size()));
  EXPECT_NE(checksum64(c.data(), c.size()), checksum64(d.data(), d.size()));
  EXPECT_NE(checksum64(nullptr, 0), checksum64(d.data(), d.size()));
}

TEST(Checksum64, FixedWidthUpdatesAreLittleEndian) {
  Checksum64 a, b;
  a.updateU32(0x04030201u);
  const unsigned char bytes[4] = {1, 2, 3, 4};
  b.update(bytes, 4);
  EXPECT_EQ(a.value(), b.value());
  Checksum64 c, d;
  c.updateDouble(1.0);
  d.updateU64(0x3ff0000000000000ull);  // IEEE-754 bits of 1.0
  EXPECT_EQ(c.value(), d.value());
}

TEST(Checksum64, UpdateBothEqualsTwoSeparateUpdates) {
  std::string s;
  for (int i = 0; i < 203; ++i) s.push_back(static_cast<char>(i * 91 + 5));
  // Every split of the prefixes, so that either hash may start mid-word (the
  // one-pass loop) or both at a word boundary, and every tail length.
  for (std::size_t pa : {0, 3, 8, 13}) {
    for (std::size_t pb : {0, 5, 16}) {
      for (std::size_t size : {0, 1, 7, 8, 64, 190}) {
        Checksum64 a, b, ra, rb;
        a.update(s.data(), pa);
        ra.update(s.data(), pa);
        b.update(s.data() + 1, pb);
        rb.update(s.data() + 1, pb);
        updateBoth(&a, &b, s.data() + 13, size);
        ra.update(s.data() + 13, size);
        rb.update(s.data() + 13, size);
        EXPECT_EQ(a.value(), ra.value()) << pa << " " << pb << " " << size;
        EXPECT_EQ(b.value(), rb.value()) << pa << " " << pb << " " << size;
        // And both go on as if fed separately.
        a.update("xyz", 3);
        ra.update("xyz", 3);
        EXPECT_EQ(a.value(), ra.value());
      }
    }
  }
}

}  // namespace
}  // namespace bowg
