// One reading of the robot's odometry, as the keyframe gate and the stamp
// merge take it: metres driven or a position. ROS-free.
#pragma once

#include <cstddef>

#include "bowg/core/types.h"

namespace bowg_ros {

/// One stamped reading of the robot's odometry: metres driven (an
/// odometer, a cable counter) or a position (nav_msgs/Odometry).
struct OdometryReading {
  enum Source { kOdometer = 0, kPosition = 1 };
  static constexpr std::size_t kSources = 2;
  Source source = kOdometer;
  double metres = 0.0;         ///< kOdometer
  double x = 0, y = 0, z = 0;  ///< kPosition (m, the odometry frame)
  /// kPosition: the heading in that frame (bowg::headingFromQuaternion of
  /// the orientation); unknown when the odometry gives none.
  bowg::OdometryHeading heading;

  static OdometryReading odometer(double metres) {
    OdometryReading r;
    r.metres = metres;
    return r;
  }
  static OdometryReading position(double x, double y, double z,
                                  const bowg::OdometryHeading& heading = bowg::OdometryHeading()) {
    OdometryReading r;
    r.source = kPosition;
    r.x = x;
    r.y = y;
    r.z = z;
    r.heading = heading;
    return r;
  }
};

}  // namespace bowg_ros
