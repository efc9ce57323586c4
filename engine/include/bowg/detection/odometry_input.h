// What odometry a keyframe comes with, which decides how its loops are
// accepted: a robot may have dead-reckoned positions and their path length,
// an odometer alone (metres driven: a crawler's cable counter), or nothing.
#pragma once

#include <cstddef>

#include "bowg/core/types.h"

namespace bowg {

enum class OdometryInput {
  kPositions,  ///< odometry positions and an odometer: the odometry gates apply
  kOdometer,   ///< metres driven only: windows in metres, the verified chain in metres
  kNone,       ///< images only: windows in keyframes, the verified chain in keyframes
};
/// How many values OdometryInput has (a count per input is an array of it).
constexpr std::size_t kOdometryInputs = 3;

/// The input of a keyframe with this odometer and position (NaN = unknown;
/// a position without an odometer places nothing: the gates need both).
OdometryInput odometryInput(double odometer, const OdometryPosition& position);

/// "positions", "odometer", "none".
const char* toString(OdometryInput input);

/// One line for a start-up log, beginning with what the input is
/// ("positions and odometer: ", "odometer only: ", "none: "), then what the
/// detector does with it.
const char* describeAcceptance(OdometryInput input);

}  // namespace bowg
