#include "bowg/detection/odometry_input.h"

#include <cmath>

namespace bowg {

OdometryInput odometryInput(double odometer, const OdometryPosition& position) {
  if (!std::isfinite(odometer)) return OdometryInput::kNone;
  return position.known() ? OdometryInput::kPositions : OdometryInput::kOdometer;
}

const char* toString(OdometryInput input) {
  switch (input) {
    case OdometryInput::kPositions:
      return "positions";
    case OdometryInput::kOdometer:
      return "odometer";
    case OdometryInput::kNone:
      return "none";
  }
  return "unknown";
}

const char* describeAcceptance(OdometryInput input) {
  switch (input) {
    case OdometryInput::kPositions:
      return "positions and odometer: windows in metres, the odometry gates (and the heading "
             "gate where the odometry has an orientation); a loop no recent loop places needs "
             "the verified chain, its unique inliers counted on average where the gate judged "
             "the match";
    case OdometryInput::kOdometer:
      return "odometer only: windows in metres (recent_exclusion_odometer_m), every loop needs "
             "the verified chain, followed in metres driven";
    case OdometryInput::kNone:
      return "none: windows in keyframes (keep them ~4 cm apart: min_keyframe_interval = "
             "0.04 m / speed), candidates above min_score + images_only_score_margin, every "
             "loop needs the verified chain, followed in keyframes";
  }
  return "unknown";
}

}  // namespace bowg
