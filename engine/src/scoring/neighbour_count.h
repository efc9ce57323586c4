// The inner loop of the word groups' neighbour search (word_groups.h): how
// many of a run of points lie within a squared distance of a point, in
// float, counted against two bounds at once (the float test and its
// uncertainty band, word_groups.cpp). Four points an SSE2 instruction (the
// compiler's vector code), or eight with AVX2 where the CPU has it: the
// same float operations, so the same counts.
#pragma once

#include <cstdint>

namespace bowg {
namespace neighbour_count {

/// Points s in [begin, end) of (xs, ys) with d2 < below (`sure`) and with
/// d2 <= above (`maybe`), d2 = (xs[s] - x)^2 + (ys[s] - y)^2 in float.
struct Counts {
  std::int32_t sure = 0;
  std::int32_t maybe = 0;
};
using CountWithin = Counts (*)(const float* xs, const float* ys, std::uint32_t begin,
                               std::uint32_t end, float x, float y, float below, float above);

Counts countWithinPortable(const float* xs, const float* ys, std::uint32_t begin,
                           std::uint32_t end, float x, float y, float below, float above);

/// Call only where cpuHasAvx2() (core/cpu_features.h); std::logic_error
/// where this build has no AVX2 version (other architectures).
Counts countWithinAvx2(const float* xs, const float* ys, std::uint32_t begin, std::uint32_t end,
                       float x, float y, float below, float above);

/// The fastest count this CPU runs, chosen once.
CountWithin bestCountWithin();

}  // namespace neighbour_count
}  // namespace bowg
