// A hint to the CPU that memory will be read soon: the inverse index's
// scattered posting lists and the vocabulary tree's child blocks are waited
// on otherwise.
#pragma once

namespace bowg {

/// Asks for the cache line at `p` (no effect where the compiler has no
/// prefetch builtin).
inline void prefetchRead(const void* p) {
#if defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

}  // namespace bowg
