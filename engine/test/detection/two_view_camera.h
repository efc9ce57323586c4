// The pinhole camera of the two-view tests (geometric verification, metric
// translation) and the angle between two rotations.
#pragma once

#include <algorithm>
#include <cmath>

#include "bowg/core/types.h"

namespace bowg {
namespace testing {

const double kPi = 3.14159265358979323846;

/// 640 x 480, f = 450 px, principal point at the centre.
inline CameraIntrinsics twoViewCamera() {
  CameraIntrinsics k;
  k.valid = true;
  k.fx = k.fy = 450;
  k.cx = 320;
  k.cy = 240;
  return k;
}

/// Angle of the rotation R_a^T R_b (degrees), both row-major 3x3.
inline double rotationErrorDeg(const double* a, const double* b) {
  double trace = 0;
  for (int i = 0; i < 9; ++i) trace += a[i] * b[i];
  return std::acos(std::max(-1.0, std::min(1.0, (trace - 1) / 2))) * 180 / kPi;
}

}  // namespace testing
}  // namespace bowg
