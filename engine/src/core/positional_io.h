// Reads and writes at an offset of an open file descriptor, whole: pread and
// pwrite may move fewer bytes than asked, and a signal may interrupt them.
// Shared by the bounded reader (bounded_file.h), the atomic writer's stream
// (atomic_file.h) and the .bowgvoc loader. Internal to the engine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace bowg {

/// Reads up to `n` bytes at `offset` into `dst`, retrying short reads; stops
/// early only at the end of the file. Returns the bytes read. Throws IoError
/// "<what>: <system error>" when a read fails.
std::size_t preadUpTo(int fd, void* dst, std::size_t n, std::uint64_t offset,
                      const std::string& what);

/// Writes all `n` bytes of `src` at `offset`, retrying short writes. Throws
/// IoError "<what>: <system error>" when a write fails.
void pwriteAll(int fd, const void* src, std::size_t n, std::uint64_t offset,
               const std::string& what);

}  // namespace bowg
