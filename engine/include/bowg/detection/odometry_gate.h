// The odometry gate (IslandOptions::odometry_gate_m): a candidate must lie
// where dead reckoning says the robot could be. In a pipe that looks the same
// every metre the visual evidence cannot tell a revisit from a look-alike a
// few metres along, but the odometry can, within its drift.
#pragma once

#include "bowg/core/types.h"
#include "bowg/database/database.h"
#include "bowg/detection/detection_options.h"

namespace bowg {

/// The largest distance (m) between the odometry positions of two entries
/// `driven_m` metres of driving apart that the gate lets through:
/// odometry_gate_m + odometry_gate_drift * driven_m.
double odometryGateRadius(const IslandOptions& options, double driven_m);

/// Whether `entry` may be a candidate of `query` by the gate: true when the
/// gate is off (odometry_gate_m 0), when either lacks a position or an
/// odometer, or when their positions belong to different odometry runs;
/// otherwise whether their distance is within odometryGateRadius of the
/// metres driven between them.
bool withinOdometryGate(const DatabaseEntry& query, const DatabaseEntry& entry,
                        const IslandOptions& options);

}  // namespace bowg
