// Crafted files for the loaders' checks: the project's binary formats
// (.bowgvoc, .bowgdb) end with checksum64 of every byte before it, little-
// endian; a test that edits a file reseals it so that only the loader's own
// checks can refuse the edit.
#pragma once

#include <cstdint>
#include <string>

#include "bowg/core/checksum.h"

namespace bowg {
namespace testing {

/// Rewrites the last 8 bytes of `bytes` as the checksum of the rest.
inline void resealChecksum(std::string* bytes) {
  const std::uint64_t sum = checksum64(bytes->data(), bytes->size() - 8);
  for (int i = 0; i < 8; ++i) {
    (*bytes)[bytes->size() - 8 + i] = static_cast<char>((sum >> (8 * i)) & 0xff);
  }
}

}  // namespace testing
}  // namespace bowg
