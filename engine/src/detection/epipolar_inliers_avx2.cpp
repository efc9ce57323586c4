// The inlier count with AVX2 (epipolar_inliers.h), compiled for AVX2
// function by function (the target attribute); the caller checks the CPU.
#include <stdexcept>

#include "detection/epipolar_inliers.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define BOWG_EPIPOLAR_INLIERS_AVX2 1
#include <immintrin.h>
#else
#define BOWG_EPIPOLAR_INLIERS_AVX2 0
#endif

namespace bowg {
namespace epipolar_inliers {

#if BOWG_EPIPOLAR_INLIERS_AVX2

namespace {

// The sum of four 64-bit counts.
__attribute__((target("avx2"))) inline int total(__m256i counts) {
  const __m128i halves =
      _mm_add_epi64(_mm256_castsi256_si128(counts), _mm256_extracti128_si256(counts, 1));
  return static_cast<int>(_mm_cvtsi128_si64(halves) +
                          _mm_cvtsi128_si64(_mm_unpackhi_epi64(halves, halves)));
}

}  // namespace

__attribute__((target("avx2"))) int countInliersAvx2(const PairArrays& pairs, std::uint32_t n,
                                                     const double f[9], double t2, int best) {
  const double* x1 = pairs.x1;
  const double* y1 = pairs.y1;
  const double* x2 = pairs.x2;
  const double* y2 = pairs.y2;
  const __m256d f0 = _mm256_set1_pd(f[0]), f1 = _mm256_set1_pd(f[1]), f2 = _mm256_set1_pd(f[2]);
  const __m256d f3 = _mm256_set1_pd(f[3]), f4 = _mm256_set1_pd(f[4]), f5 = _mm256_set1_pd(f[5]);
  const __m256d f6 = _mm256_set1_pd(f[6]), f7 = _mm256_set1_pd(f[7]), f8 = _mm256_set1_pd(f[8]);
  const __m256d tt = _mm256_set1_pd(t2), zero = _mm256_setzero_pd();
  // The compare masks (all ones: -1) subtracted from 64-bit counts.
  __m256i counts = _mm256_setzero_si256();
  std::uint32_t i = 0;
  while (i + 4 <= n) {
    const std::uint32_t block_end = i + kBlock <= n ? i + kBlock : n - (n - i) % 4;
    for (; i < block_end; i += 4) {
      const __m256d px1 = _mm256_loadu_pd(x1 + i), py1 = _mm256_loadu_pd(y1 + i);
      const __m256d px2 = _mm256_loadu_pd(x2 + i), py2 = _mm256_loadu_pd(y2 + i);
      const __m256d l2a =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(f0, px1), _mm256_mul_pd(f1, py1)), f2);
      const __m256d l2b =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(f3, px1), _mm256_mul_pd(f4, py1)), f5);
      const __m256d l2c =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(f6, px1), _mm256_mul_pd(f7, py1)), f8);
      const __m256d l1a =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(f0, px2), _mm256_mul_pd(f3, py2)), f6);
      const __m256d l1b =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(f1, px2), _mm256_mul_pd(f4, py2)), f7);
      const __m256d n2 = _mm256_add_pd(_mm256_mul_pd(l2a, l2a), _mm256_mul_pd(l2b, l2b));
      const __m256d n1 = _mm256_add_pd(_mm256_mul_pd(l1a, l1a), _mm256_mul_pd(l1b, l1b));
      const __m256d normal = _mm256_min_pd(n1, n2);  // n1 < n2 ? n1 : n2
      const __m256d residual =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(px2, l2a), _mm256_mul_pd(py2, l2b)), l2c);
      // Ordered compares: a NaN is no inlier, as in the scalar test.
      const __m256d inlier =
          _mm256_and_pd(_mm256_cmp_pd(normal, zero, _CMP_GT_OQ),
                        _mm256_cmp_pd(_mm256_mul_pd(residual, residual),
                                      _mm256_mul_pd(tt, normal), _CMP_LE_OQ));
      counts = _mm256_sub_epi64(counts, _mm256_castpd_si256(inlier));
    }
    if (total(counts) + static_cast<int>(n - i) <= best) return total(counts);
  }
  return total(counts) + countInliersScalar(pairs, f, t2, i, n);
}

#else

int countInliersAvx2(const PairArrays&, std::uint32_t, const double*, double, int) {
  throw std::logic_error("countInliersAvx2: this build has no AVX2 version");
}

#endif

}  // namespace epipolar_inliers
}  // namespace bowg
