// The ground-truth file of the offline evaluation ("query: matches" lines).
// Documented outcomes: a GroundTruth or FormatError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "bowg/core/errors.h"
#include "bowg_evaluation/ground_truth.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    bowg::eval::parseGroundTruth(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const bowg::FormatError&) {
  }
  return 0;
}
