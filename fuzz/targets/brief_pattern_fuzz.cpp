// The BRIEF pattern file (VINS' brief_pattern.yml layout). Documented
// outcomes: 256 tests, FormatError or IoError.
#include <cstddef>
#include <cstdint>

#include "bowg/core/errors.h"
#include "bowg/features/brief_pattern.h"
#include "fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = bowg::fuzz::writeInput(data, size, ".yml");
  try {
    if (bowg::loadBriefPattern(path).size() != 256) __builtin_trap();
  } catch (const bowg::FormatError&) {
  } catch (const bowg::IoError&) {
  }
  return 0;
}
