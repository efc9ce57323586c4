// The robot's heading from its odometry's orientation, and the angle between
// two headings: what the heading gate (odometry_gate.h) compares.
#pragma once

#include "bowg/core/types.h"

namespace bowg {

/// The body x axis (forward, REP-103) of the rotation given by the
/// quaternion (qx, qy, qz, qw), in the frame the orientation is given in:
/// the first column of its rotation matrix,
///   (1 - 2(qy^2 + qz^2), 2(qx qy + qz qw), 2(qx qz - qy qw)),
/// of the quaternion scaled to unit length. Unknown when a component is not
/// finite or the norm is not within 0.01 of 1: a zeroed or garbled
/// orientation (some drivers publish (0, 0, 0, 0) when they have none) is
/// no heading.
OdometryHeading headingFromQuaternion(double qx, double qy, double qz, double qw);

/// The angle (degrees, [0, 180]) between two known headings.
double headingAngleDeg(const OdometryHeading& a, const OdometryHeading& b);

}  // namespace bowg
