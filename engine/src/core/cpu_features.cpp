#include "core/cpu_features.h"

namespace bowg {

bool cpuHasAvx2() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  // GCC's and Clang's check also asks whether the operating system saves
  // the AVX registers.
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") != 0;
#else
  return false;
#endif
}

}  // namespace bowg
