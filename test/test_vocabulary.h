// A small vocabulary for the rostests, trained at test time with the
// engine's trainer (bowg::trainVocabulary) on synthetic textures that are not
// the test sequences, until the project's default vocabulary lands in data/.
#pragma once

#include <string>

namespace bowg_ros {
namespace test {

/// Trains (k = 8, L = 3) and saves a vocabulary to `path` unless the file
/// already exists; returns `path`.
std::string ensureTestVocabulary(const std::string& path);

}  // namespace test
}  // namespace bowg_ros
