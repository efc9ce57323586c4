// What the CPU running the engine offers beyond the build's baseline, for
// the few loops that have a faster version for it (chosen once at run time,
// so that one library runs on every x86-64 CPU with popcount).
#pragma once

namespace bowg {

/// Whether this CPU and its operating system run AVX2 code (false on other
/// architectures and compilers without the check).
bool cpuHasAvx2();

}  // namespace bowg
