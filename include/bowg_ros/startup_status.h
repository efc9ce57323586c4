// Why a LoopDetectorNodelet did not start, for whoever loaded it in the same
// process: the standalone loop_detector_node exits non-zero with the reason
// (a nodelet's onInit cannot fail its loader).
#pragma once

#include <string>

namespace bowg_ros {

/// Records that the nodelet named `nodelet` did not start, and why.
void reportStartupFailure(const std::string& nodelet, const std::string& why);

/// Whether the nodelet named `nodelet` reported a start-up failure; its
/// reason in `why`.
bool startupFailed(const std::string& nodelet, std::string* why);

}  // namespace bowg_ros
