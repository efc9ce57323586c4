// Every on-disk format of the engine is little-endian whatever the host:
// values are assembled byte by byte (compilers make this one load on a
// little-endian CPU). Internal to the engine.
#pragma once

#include <cstddef>

namespace bowg {

/// The unsigned integer T stored little-endian at `p`.
template <typename T>
inline T loadLittleEndian(const unsigned char* p) {
  T v = 0;
  for (std::size_t i = sizeof(T); i-- > 0;) v = static_cast<T>((v << 8) | p[i]);
  return v;
}

}  // namespace bowg
