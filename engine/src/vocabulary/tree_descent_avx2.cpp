// The tree descent with AVX2 (tree_descent.h), compiled for AVX2 function by
// function (the target attribute) so that the library itself still runs on
// any x86-64 CPU with popcount; the caller checks the CPU first.
#include <stdexcept>

#include "vocabulary/tree_descent.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define BOWG_TREE_DESCENT_AVX2 1
#include <immintrin.h>
#else
#define BOWG_TREE_DESCENT_AVX2 0
#endif

namespace bowg {
namespace tree_descent {

#if BOWG_TREE_DESCENT_AVX2

namespace {

using Node = Vocabulary::Node;

// The set bits of each 64-bit lane of `x`: the bytes' counts from a nibble
// table (AVX2 has no vector popcount), summed per lane by a sum of absolute
// differences against zero. Each lane's count is at most 64.
__attribute__((target("avx2"))) inline __m256i laneBitCounts(__m256i x) {
  const __m256i table = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4,  //
                                         0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4);
  const __m256i low_nibbles = _mm256_set1_epi8(0x0f);
  const __m256i lo = _mm256_and_si256(x, low_nibbles);
  const __m256i hi = _mm256_and_si256(_mm256_srli_epi16(x, 4), low_nibbles);
  const __m256i bytes =
      _mm256_add_epi8(_mm256_shuffle_epi8(table, lo), _mm256_shuffle_epi8(table, hi));
  return _mm256_sad_epu8(bytes, _mm256_setzero_si256());
}

// The Hamming distances of `q` to the descriptors of nodes child[0..n)
// (n <= 4), packed as 16-bit fields, child c's in bits 16c..16c+15; a field
// without a child holds 0xffff, farther than any distance (<= 256). Each
// child's four lane counts go to its field of every lane, and the lanes are
// added: a field sums to at most 256 (or 0xffff), so none carries into the
// next.
__attribute__((target("avx2"))) inline std::uint64_t fourDistances(__m256i q, const Node* child,
                                                                   int n) {
  __m256i packed = _mm256_setzero_si256();
  for (int c = 0; c < 4; ++c) {
    const __m256i counts =
        c < n ? laneBitCounts(_mm256_xor_si256(
                    q, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&child[c].descriptor))))
              : _mm256_setr_epi64x(0xffff, 0, 0, 0);
    packed = _mm256_or_si256(packed, _mm256_slli_epi64(counts, 16 * c));
  }
  const __m128i pairs =
      _mm_add_epi64(_mm256_castsi256_si128(packed), _mm256_extracti128_si256(packed, 1));
  return static_cast<std::uint64_t>(_mm_cvtsi128_si64(pairs)) +
         static_cast<std::uint64_t>(_mm_cvtsi128_si64(_mm_unpackhi_epi64(pairs, pairs)));
}

}  // namespace

__attribute__((target("avx2"))) void descendBatchAvx2(const Node* nodes, const Descriptor* d,
                                                      std::size_t count, int level, WordId* words,
                                                      NodeId* at_level) {
  std::uint32_t current[kBatch];
  for (std::size_t g = 0; g < count; ++g) {
    current[g] = 0;
    at_level[g] = 0;
  }
  for (bool moved = true; moved;) {
    moved = false;
    for (std::size_t g = 0; g < count; ++g) {
      const Node& node = nodes[current[g]];
      if (node.num_children == 0) continue;
      const __m256i q = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&d[g]));
      const Node* child = nodes + node.first_child;
      const int n = static_cast<int>(node.num_children);
      // Eight children at a time: the smallest of eight 16-bit distances
      // and its position in one instruction (SSE4.1's minpos, the first
      // position among equals); a later group wins only when strictly
      // nearer. So the first of equally near children, as the portable loop.
      int best = 0, best_distance = 1 << 30;
      for (int base = 0; base < n; base += 8) {
        const int m = n - base < 8 ? n - base : 8;
        const std::uint64_t first = fourDistances(q, child + base, m);
        const std::uint64_t second = m > 4 ? fourDistances(q, child + base + 4, m - 4) : ~0ULL;
        const __m128i found = _mm_minpos_epu16(_mm_set_epi64x(static_cast<long long>(second),
                                                              static_cast<long long>(first)));
        const int distance = _mm_extract_epi16(found, 0);
        if (distance < best_distance) {
          best_distance = distance;
          best = base + _mm_extract_epi16(found, 1);
        }
      }
      moveTo(nodes, node.first_child + static_cast<std::uint32_t>(best), level, &current[g],
             &at_level[g]);
      moved = true;
    }
  }
  for (std::size_t g = 0; g < count; ++g) words[g] = nodes[current[g]].word;
}

#else

void descendBatchAvx2(const Vocabulary::Node*, const Descriptor*, std::size_t, int, WordId*,
                      NodeId*) {
  throw std::logic_error("descendBatchAvx2: this build has no AVX2 version");
}

#endif

}  // namespace tree_descent
}  // namespace bowg
