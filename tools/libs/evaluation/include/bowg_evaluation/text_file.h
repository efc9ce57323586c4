// Whole text files of the tools (ground truth, odometry, trajectories, loops).
#pragma once

#include <string>

namespace bowg {
namespace eval {

/// The whole file. Throws bowg::IoError "cannot read the <what> file <path>:
/// <reason>" when it cannot be opened.
std::string readTextFile(const std::string& path, const std::string& what);

}  // namespace eval
}  // namespace bowg
