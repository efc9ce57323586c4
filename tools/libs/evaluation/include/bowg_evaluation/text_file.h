// Whole text files of the tools (ground truth, odometry, trajectories, loops).
#pragma once

#include <string>

namespace bowg {
namespace eval {

/// The whole file. Throws bowg::IoError "cannot open|read the <what> file
/// '<path>': <reason>" when it is missing or unreadable, not a regular file,
/// or larger than BOWG_MAX_TEXT_MB (bounded_file.h).
std::string readTextFile(const std::string& path, const std::string& what);

}  // namespace eval
}  // namespace bowg
