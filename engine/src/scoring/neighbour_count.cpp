// The portable neighbour count and the choice between it and the AVX2 one
// (neighbour_count.h).
#include "scoring/neighbour_count.h"

#include "core/cpu_features.h"

namespace bowg {
namespace neighbour_count {

Counts countWithinPortable(const float* xs, const float* ys, std::uint32_t begin,
                           std::uint32_t end, float x, float y, float below, float above) {
  // 32-bit counts of 32-bit compares: the loop vectorises as integer sums
  // (a floating-point sum would not, without reassociation).
  std::int32_t sure = 0, maybe = 0;
  for (std::uint32_t s = begin; s < end; ++s) {
    const float dx = xs[s] - x;
    const float dy = ys[s] - y;
    const float d2 = dx * dx + dy * dy;
    sure += d2 < below;
    maybe += d2 <= above;
  }
  return Counts{sure, maybe};
}

CountWithin bestCountWithin() {
  static const CountWithin best = cpuHasAvx2() ? countWithinAvx2 : countWithinPortable;
  return best;
}

}  // namespace neighbour_count
}  // namespace bowg
