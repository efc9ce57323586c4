#include "bowg/detection/odometry_gate.h"

#include <cmath>

namespace bowg {

double odometryGateRadius(const IslandOptions& options, double driven_m) {
  return options.odometry_gate_m + options.odometry_gate_drift * std::fabs(driven_m);
}

bool withinOdometryGate(const DatabaseEntry& query, const DatabaseEntry& entry,
                        const IslandOptions& options) {
  if (!(options.odometry_gate_m > 0.0)) return true;
  if (!query.position.known() || !entry.position.known()) return true;
  if (query.odometry_run != entry.odometry_run) return true;
  if (!std::isfinite(query.odometer) || !std::isfinite(entry.odometer)) return true;
  const double dx = query.position.x - entry.position.x;
  const double dy = query.position.y - entry.position.y;
  const double dz = query.position.z - entry.position.z;
  const double radius = odometryGateRadius(options, query.odometer - entry.odometer);
  return dx * dx + dy * dy + dz * dz <= radius * radius;
}

}  // namespace bowg
