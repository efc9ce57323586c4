// The process's resident set, to set the engine's memory estimates
// (Database::memoryBytes()) against what the process really holds.
#pragma once

namespace bowg {

/// Bytes of the process's resident set (Linux /proc/self/statm); 0 where the
/// system does not tell.
double residentBytes();

}  // namespace bowg
