// The neighbour count with AVX2 (neighbour_count.h), compiled for AVX2
// function by function (the target attribute); the caller checks the CPU.
#include <stdexcept>

#include "scoring/neighbour_count.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define BOWG_NEIGHBOUR_COUNT_AVX2 1
#include <immintrin.h>
#else
#define BOWG_NEIGHBOUR_COUNT_AVX2 0
#endif

namespace bowg {
namespace neighbour_count {

#if BOWG_NEIGHBOUR_COUNT_AVX2

namespace {

// The sum of eight 32-bit counts.
__attribute__((target("avx2"))) inline std::int32_t total(__m256i counts) {
  __m128i s = _mm_add_epi32(_mm256_castsi256_si128(counts), _mm256_extracti128_si256(counts, 1));
  s = _mm_add_epi32(s, _mm_unpackhi_epi64(s, s));
  s = _mm_add_epi32(s, _mm_shuffle_epi32(s, 1));
  return _mm_cvtsi128_si32(s);
}

}  // namespace

__attribute__((target("avx2"))) Counts countWithinAvx2(const float* xs, const float* ys,
                                                       std::uint32_t begin, std::uint32_t end,
                                                       float x, float y, float below,
                                                       float above) {
  const __m256 vx = _mm256_set1_ps(x), vy = _mm256_set1_ps(y);
  const __m256 vbelow = _mm256_set1_ps(below), vabove = _mm256_set1_ps(above);
  // The compare masks (all ones: -1) subtracted from the counts; ordered
  // compares, false for a NaN as in the scalar test.
  __m256i sure = _mm256_setzero_si256(), maybe = _mm256_setzero_si256();
  std::uint32_t s = begin;
  for (; s + 8 <= end; s += 8) {
    const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(xs + s), vx);
    const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(ys + s), vy);
    const __m256 d2 = _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy));
    sure = _mm256_sub_epi32(sure, _mm256_castps_si256(_mm256_cmp_ps(d2, vbelow, _CMP_LT_OQ)));
    maybe = _mm256_sub_epi32(maybe, _mm256_castps_si256(_mm256_cmp_ps(d2, vabove, _CMP_LE_OQ)));
  }
  if (s < end) {
    // The last 1-7 points by a masked load (lanes past the end read nothing
    // and count nothing): most runs of a grid row are that short.
    static const std::int32_t kLanes[16] = {-1, -1, -1, -1, -1, -1, -1, -1, 0, 0, 0, 0, 0, 0, 0, 0};
    const __m256i lanes =
        _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kLanes + 8 - (end - s)));
    const __m256 dx = _mm256_sub_ps(_mm256_maskload_ps(xs + s, lanes), vx);
    const __m256 dy = _mm256_sub_ps(_mm256_maskload_ps(ys + s, lanes), vy);
    const __m256 d2 = _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy));
    sure = _mm256_sub_epi32(
        sure, _mm256_and_si256(lanes, _mm256_castps_si256(_mm256_cmp_ps(d2, vbelow, _CMP_LT_OQ))));
    maybe = _mm256_sub_epi32(
        maybe, _mm256_and_si256(lanes, _mm256_castps_si256(_mm256_cmp_ps(d2, vabove, _CMP_LE_OQ))));
  }
  return Counts{total(sure), total(maybe)};
}

#else

Counts countWithinAvx2(const float*, const float*, std::uint32_t, std::uint32_t, float, float,
                       float, float) {
  throw std::logic_error("countWithinAvx2: this build has no AVX2 version");
}

#endif

}  // namespace neighbour_count
}  // namespace bowg
