// Where the benchmarks find ../shared/data: the build's BOWG_SHARED_DATA_DIR,
// overridden by the environment variable of the same name.
#pragma once

#include <cstdlib>
#include <string>

namespace bowg {
namespace bench {

inline std::string sharedDataDir() {
  if (const char* env = std::getenv("BOWG_SHARED_DATA_DIR")) return env;
  return BOWG_SHARED_DATA_DIR;
}

}  // namespace bench
}  // namespace bowg
