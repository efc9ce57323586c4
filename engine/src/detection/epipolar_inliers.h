// Counting the pairs a fundamental matrix accepts, RANSAC's inner loop
// (fundamental_ransac.h): the pairs' coordinates one array each, tested two
// at a time with SSE2, or four with AVX2 where the CPU has it, with the
// operations of epipolarResidual in its order, so that every version counts
// what isInlier accepts pair by pair (no fused multiply-adds: this build
// does not contract them, and the vector code names each operation).
#pragma once

#include <cstdint>

namespace bowg {
namespace epipolar_inliers {

/// Pairs i of four coordinate arrays: (x1[i], y1[i]) in the first image,
/// (x2[i], y2[i]) in the second.
struct PairArrays {
  const double* x1;
  const double* y1;
  const double* x2;
  const double* y2;
};

/// How many of the n pairs model f (row-major) accepts: those whose
/// epipolarResidual (residual r, normal m: the smaller squared gradient of
/// the two epipolar lines) has m > 0 and r^2 <= t2 * m, i.e. both images'
/// distances to their epipolar lines at most sqrt(t2). Gives up once the
/// count cannot exceed `best` (checked every kBlock pairs) and then returns
/// at most `best`: RANSAC only needs to know that the model is no better.
using CountInliers = int (*)(const PairArrays& pairs, std::uint32_t n, const double f[9],
                             double t2, int best);

/// Pairs tested between the checks of the count against `best`.
constexpr std::uint32_t kBlock = 8;

/// Two pairs an SSE2 instruction on x86-64, the compiler's vector code
/// elsewhere.
int countInliersPortable(const PairArrays& pairs, std::uint32_t n, const double f[9], double t2,
                         int best);

/// Four pairs an AVX2 instruction. Call only where cpuHasAvx2()
/// (core/cpu_features.h); std::logic_error where this build has no AVX2
/// version (other architectures).
int countInliersAvx2(const PairArrays& pairs, std::uint32_t n, const double f[9], double t2,
                     int best);

/// The scalar test of pairs [begin, end), without giving up: the tail of
/// the vector counts.
int countInliersScalar(const PairArrays& pairs, const double f[9], double t2, std::uint32_t begin,
                       std::uint32_t end);

/// The fastest count this CPU runs, chosen once.
CountInliers bestCountInliers();

}  // namespace epipolar_inliers
}  // namespace bowg
