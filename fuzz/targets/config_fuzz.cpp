// The configuration file (config/*.yaml, the flat yaml subset of the
// parameter table). Documented outcomes: valid options, FormatError,
// IoError or InvalidParameter naming the key.
#include <cstddef>
#include <cstdint>

#include "bowg/core/errors.h"
#include "bowg/parameters/parameter_table.h"
#include "fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = bowg::fuzz::writeInput(data, size, ".yaml");
  try {
    bowg::loadParameterFile(path).validate();
  } catch (const bowg::FormatError&) {
  } catch (const bowg::IoError&) {
  } catch (const bowg::InvalidParameter&) {
  }
  return 0;
}
