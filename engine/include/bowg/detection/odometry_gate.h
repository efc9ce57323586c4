// The odometry gates (IslandOptions::odometry_gate_m, odometry_anchor_m): a
// candidate must lie where dead reckoning says the robot could be. In a pipe
// that looks the same every metre the visual evidence cannot tell a revisit
// from a look-alike a few metres along, but the odometry can, within its
// drift.
#pragma once

#include "bowg/core/types.h"
#include "bowg/database/database.h"
#include "bowg/detection/detection_options.h"

namespace bowg {

/// The last accepted loop of the current odometry run: where the robot was
/// (`query`, an entry once its query is done) and the earlier entry it was
/// recognised at (`match`). Not saved with the detector: a loaded detector
/// starts a new odometry run, in which an old anchor never applies.
struct LoopAnchor {
  bool set = false;
  EntryId query = 0;
  EntryId match = 0;
};

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

/// The loop-anchored gate's radius (m) when the query drove `query_driven_m`
/// since the anchor's query and the entry lies `entry_driven_m` along the
/// earlier passes from the anchor's match: odometry_anchor_m +
/// odometry_gate_drift * (|query_driven_m| + |entry_driven_m|). An entry on
/// another lap than the anchor's match is a lap of driving away from it, so
/// its radius is as wide as the absolute gate's.
double loopAnchorRadius(const IslandOptions& options, double query_driven_m, double entry_driven_m);

/// Whether `entry` may be a candidate of `query` by the loop-anchored gate,
/// with `anchor_query` and `anchor_match` the entries of the last accepted
/// loop: true when the gate is off (odometry_anchor_m 0) or when any of the
/// four lacks a position or an odometer or belongs to another odometry run;
/// otherwise whether the displacements (query - anchor_query) and (entry -
/// anchor_match) differ by at most loopAnchorRadius.
bool withinLoopAnchor(const DatabaseEntry& query, const DatabaseEntry& entry,
                      const DatabaseEntry& anchor_query, const DatabaseEntry& anchor_match,
                      const IslandOptions& options);

}  // namespace bowg
