// The detector file tests' older versions: a saved file rewritten as an
// older version wrote it, and the sizes of the sections later versions append.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "core/resealed_checksum.h"

namespace bowg {
namespace testing {

// Writes `v` little-endian in `n` bytes at `at`.
inline void putLe(std::string* bytes, std::size_t at, std::uint64_t v, int n) {
  for (int i = 0; i < n; ++i) (*bytes)[at + i] = static_cast<char>((v >> (8 * i)) & 0xff);
}

// The version-7 section of a file of `n` entries: the current odometry run
// (u32), then a u32 count and each entry's u32 run and three f64.
inline std::size_t odometryPositionBytes(std::size_t n) { return 4 + 4 + n * (4 + 3 * 8); }
// The version-8 section: a u32 count and each entry's u8 searchable flag.
inline std::size_t searchableBytes(std::size_t n) { return 4 + n; }
// The version-9 section of a detector with the unnamed mission 0 alone:
// the current mission, a count, id 0 and an empty name, then a count and
// each entry's u32 mission.
inline std::size_t unnamedMissionBytes(std::size_t n) { return 4 + 4 + 4 + 4 + 4 + 4 * n; }
// The version-10 section: a u32 count and each entry's three f32 heading.
inline std::size_t headingBytes(std::size_t n) { return 4 + n * 3 * 4; }
// Everything from the version-9 / version-8 / version-7 section on (one
// unnamed mission).
inline std::size_t fromVersion9Bytes(std::size_t n) {
  return unnamedMissionBytes(n) + headingBytes(n);
}
inline std::size_t fromVersion8Bytes(std::size_t n) {
  return searchableBytes(n) + fromVersion9Bytes(n);
}
inline std::size_t fromVersion7Bytes(std::size_t n) {
  return odometryPositionBytes(n) + fromVersion8Bytes(n);
}

// A saved detector file as version `version` wrote it: without the last
// `dropped` payload bytes (the sections later versions append), its
// version, payload size (the header is 28 bytes) and checksum rewritten.
inline std::string asVersion(std::string bytes, std::size_t dropped, std::uint32_t version) {
  EXPECT_GT(bytes.size(), dropped + 8 + 28);
  bytes.resize(bytes.size() - 8 - dropped);
  putLe(&bytes, 8, version, 4);
  putLe(&bytes, 20, bytes.size() - 28, 8);
  bytes.resize(bytes.size() + 8);
  testing::resealChecksum(&bytes);
  return bytes;
}

}  // namespace testing
}  // namespace bowg
