// The portable inlier count and the choice between it and the AVX2 one
// (epipolar_inliers.h).
#include "detection/epipolar_inliers.h"

#include "bowg/detection/fundamental_matrix.h"
#include "core/cpu_features.h"

#if defined(__SSE2__) && defined(__x86_64__)
#include <emmintrin.h>
#define BOWG_EPIPOLAR_INLIERS_SSE2 1
#else
#define BOWG_EPIPOLAR_INLIERS_SSE2 0
#endif

namespace bowg {
namespace epipolar_inliers {

// epipolarResidual's test pair by pair: a double count of 0/1 factors,
// which the compiler vectorises where it can (exact below 2^53).
int countInliersScalar(const PairArrays& pairs, const double f[9], double t2, std::uint32_t i,
                       std::uint32_t end) {
  double count = 0;
  for (; i < end; ++i) {
    const EpipolarResidual e =
        epipolarResidual(f, PointPair{pairs.x1[i], pairs.y1[i], pairs.x2[i], pairs.y2[i]});
    count += (e.normal > 0.0 ? 1.0 : 0.0) * (e.residual * e.residual <= t2 * e.normal ? 1.0 : 0.0);
  }
  return static_cast<int>(count);
}

int countInliersPortable(const PairArrays& pairs, std::uint32_t n, const double f[9], double t2,
                         int best) {
#if BOWG_EPIPOLAR_INLIERS_SSE2
  const double* x1 = pairs.x1;
  const double* y1 = pairs.y1;
  const double* x2 = pairs.x2;
  const double* y2 = pairs.y2;
  const __m128d f0 = _mm_set1_pd(f[0]), f1 = _mm_set1_pd(f[1]), f2 = _mm_set1_pd(f[2]);
  const __m128d f3 = _mm_set1_pd(f[3]), f4 = _mm_set1_pd(f[4]), f5 = _mm_set1_pd(f[5]);
  const __m128d f6 = _mm_set1_pd(f[6]), f7 = _mm_set1_pd(f[7]), f8 = _mm_set1_pd(f[8]);
  const __m128d tt = _mm_set1_pd(t2), zero = _mm_setzero_pd();
  // The compare masks (all ones: -1) subtracted from 64-bit counts: left to
  // the compiler, the count is a chain of scalar additions, one per pair.
  __m128i counts = _mm_setzero_si128();
  const auto total = [&counts] {
    return static_cast<int>(_mm_cvtsi128_si64(counts) +
                            _mm_cvtsi128_si64(_mm_unpackhi_epi64(counts, counts)));
  };
  std::uint32_t i = 0;
  while (i + 2 <= n) {
    const std::uint32_t block_end = i + kBlock <= n ? i + kBlock : n - (n - i) % 2;
    for (; i < block_end; i += 2) {
      const __m128d px1 = _mm_loadu_pd(x1 + i), py1 = _mm_loadu_pd(y1 + i);
      const __m128d px2 = _mm_loadu_pd(x2 + i), py2 = _mm_loadu_pd(y2 + i);
      const __m128d l2a = _mm_add_pd(_mm_add_pd(_mm_mul_pd(f0, px1), _mm_mul_pd(f1, py1)), f2);
      const __m128d l2b = _mm_add_pd(_mm_add_pd(_mm_mul_pd(f3, px1), _mm_mul_pd(f4, py1)), f5);
      const __m128d l2c = _mm_add_pd(_mm_add_pd(_mm_mul_pd(f6, px1), _mm_mul_pd(f7, py1)), f8);
      const __m128d l1a = _mm_add_pd(_mm_add_pd(_mm_mul_pd(f0, px2), _mm_mul_pd(f3, py2)), f6);
      const __m128d l1b = _mm_add_pd(_mm_add_pd(_mm_mul_pd(f1, px2), _mm_mul_pd(f4, py2)), f7);
      const __m128d n2 = _mm_add_pd(_mm_mul_pd(l2a, l2a), _mm_mul_pd(l2b, l2b));
      const __m128d n1 = _mm_add_pd(_mm_mul_pd(l1a, l1a), _mm_mul_pd(l1b, l1b));
      const __m128d normal = _mm_min_pd(n1, n2);  // n1 < n2 ? n1 : n2
      const __m128d residual =
          _mm_add_pd(_mm_add_pd(_mm_mul_pd(px2, l2a), _mm_mul_pd(py2, l2b)), l2c);
      const __m128d inlier =
          _mm_and_pd(_mm_cmpgt_pd(normal, zero),
                     _mm_cmple_pd(_mm_mul_pd(residual, residual), _mm_mul_pd(tt, normal)));
      counts = _mm_sub_epi64(counts, _mm_castpd_si128(inlier));
    }
    if (total() + static_cast<int>(n - i) <= best) return total();
  }
  return total() + countInliersScalar(pairs, f, t2, i, n);
#else
  int count = 0;
  for (std::uint32_t begin = 0; begin < n; begin += kBlock) {
    const std::uint32_t end = begin + kBlock < n ? begin + kBlock : n;
    count += countInliersScalar(pairs, f, t2, begin, end);
    if (count + static_cast<int>(n - end) <= best) break;
  }
  return count;
#endif
}

CountInliers bestCountInliers() {
  static const CountInliers best = cpuHasAvx2() ? countInliersAvx2 : countInliersPortable;
  return best;
}

}  // namespace epipolar_inliers
}  // namespace bowg
