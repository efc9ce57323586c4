// Loaders read files: each fuzz input is written to one temporary file per
// process (reused: libFuzzer runs inputs one after another) and the loader
// reads it from there.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace bowg {
namespace fuzz {

inline std::string writeInput(const std::uint8_t* data, std::size_t size, const char* suffix) {
  static const std::string path =
      "/tmp/bowg_fuzz_" + std::to_string(static_cast<long>(::getpid())) + suffix;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) __builtin_trap();  // the harness itself is broken
  if (size > 0 && std::fwrite(data, 1, size, f) != size) __builtin_trap();
  std::fclose(f);
  return path;
}

}  // namespace fuzz
}  // namespace bowg
