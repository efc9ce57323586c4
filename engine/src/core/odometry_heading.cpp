#include "bowg/core/odometry_heading.h"

#include <algorithm>
#include <cmath>

namespace bowg {

OdometryHeading headingFromQuaternion(double qx, double qy, double qz, double qw) {
  OdometryHeading h;
  if (!(std::isfinite(qx) && std::isfinite(qy) && std::isfinite(qz) && std::isfinite(qw))) {
    return h;
  }
  const double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
  if (!(std::abs(norm - 1.0) <= 0.01)) return h;
  qx /= norm;
  qy /= norm;
  qz /= norm;
  qw /= norm;
  const double x = 1.0 - 2.0 * (qy * qy + qz * qz);
  const double y = 2.0 * (qx * qy + qz * qw);
  const double z = 2.0 * (qx * qz - qy * qw);
  // A unit quaternion's column is a unit vector; renormalise what rounding
  // leaves of it.
  const double length = std::sqrt(x * x + y * y + z * z);
  h.x = static_cast<float>(x / length);
  h.y = static_cast<float>(y / length);
  h.z = static_cast<float>(z / length);
  return h;
}

double headingAngleDeg(const OdometryHeading& a, const OdometryHeading& b) {
  const double dot = static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y +
                     static_cast<double>(a.z) * b.z;
  // acos of a dot product clamped against rounding past +-1.
  return std::acos(std::max(-1.0, std::min(1.0, dot))) * 180.0 / M_PI;
}

}  // namespace bowg
