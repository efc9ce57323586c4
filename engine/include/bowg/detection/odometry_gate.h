// The odometry gates (IslandOptions::odometry_gate_m, odometry_anchor_m): a
// candidate must lie where dead reckoning says the robot could be. In a pipe
// that looks the same every metre the visual evidence cannot tell a revisit
// from a look-alike a few metres along, but the odometry can, within its
// drift.
#pragma once

#include <cstddef>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/database/database.h"
#include "bowg/detection/detection_options.h"

namespace bowg {

/// An accepted loop of the current odometry run: where the robot was
/// (`query`, an entry once its query is done) and the earlier entry it was
/// recognised at (`match`). Not saved with the detector: a loaded detector
/// starts a new odometry run, in which an old anchor never applies.
struct LoopAnchor {
  EntryId query = 0;
  EntryId match = 0;
};

/// The loop-anchored gate remembers this many of the last accepted loops
/// (DetectorState::recent_loops). On a circuit driven lap after lap the
/// re-ranking's match jumps between the earlier laps from query to query,
/// so the last few loops hold a recent anchor on each lap the robot is
/// recognised on; an older one only widens its radius (loopAnchorRadius).
constexpr std::size_t kLoopAnchors = 8;

/// The largest distance (m) between the odometry positions of two entries
/// `driven_m` metres of driving apart that the gate lets through:
/// odometry_gate_m + odometry_gate_drift * driven_m.
double odometryGateRadius(const IslandOptions& options, double driven_m);

/// Whether the gate judges `entry` as a candidate of `query`: it is on
/// (odometry_gate_m > 0) and both have a position and an odometer of the
/// query's odometry run.
bool odometryGateApplies(const DatabaseEntry& query, const DatabaseEntry& entry,
                         const IslandOptions& options);

/// Whether `entry` may be a candidate of `query` by the gate: true when the
/// gate is off (odometry_gate_m 0), when either lacks a position or an
/// odometer, or when their positions belong to different odometry runs;
/// otherwise whether their distance is within odometryGateRadius of the
/// metres driven between them.
bool withinOdometryGate(const DatabaseEntry& query, const DatabaseEntry& entry,
                        const IslandOptions& options);

/// The largest angle (degrees) between the headings of two entries
/// `driven_m` metres of driving apart that the heading gate lets through:
/// heading_gate_deg + heading_gate_drift_deg * sqrt(|driven_m|).
double headingGateBound(const IslandOptions& options, double driven_m);

/// Whether `entry` may be a candidate of `query` by the heading gate: true
/// when the gate is off (heading_gate_deg 0), when either lacks a heading or
/// an odometer, or when they belong to different odometry runs (another
/// run's headings are in another frame); otherwise whether the angle
/// between their headings is within headingGateBound of the metres driven
/// between them.
bool withinHeadingGate(const DatabaseEntry& query, const DatabaseEntry& entry,
                       const IslandOptions& options);

/// The loop-anchored gate's radius (m) when the query drove `query_driven_m`
/// since the anchor's query and the entry lies `entry_driven_m` along the
/// earlier passes from the anchor's match: odometry_anchor_m +
/// odometry_gate_drift * (|query_driven_m| + |entry_driven_m|). An entry on
/// another lap than the anchor's match is a lap of driving away from it, so
/// its radius is as wide as the absolute gate's.
double loopAnchorRadius(const IslandOptions& options, double query_driven_m, double entry_driven_m);

/// An accepted loop's two entries, as the loop-anchored gate reads them.
struct AnchorEntries {
  const DatabaseEntry* query;
  const DatabaseEntry* match;
};

/// Whether `entry` may be a candidate of `query` by the loop-anchored gate.
/// It is judged by the anchor that predicts its place best: the one whose
/// loopAnchorRadius for it is the smallest among the `anchors` that apply
/// (query, entry and both of the anchor's entries carry a position and an
/// odometer of the query's odometry run). By that anchor, the displacements
/// (query - anchor query) and (entry - anchor match) must differ by at most
/// that radius. True when no anchor applies or the gate is off
/// (odometry_anchor_m 0).
bool withinLoopAnchors(const DatabaseEntry& query, const DatabaseEntry& entry,
                       const std::vector<AnchorEntries>& anchors, const IslandOptions& options);

/// The cross-run gate: after an accepted loop (q0, m0) from the query's
/// odometry run into another one (a later mission into an earlier one's
/// keyframes, a restarted robot into its loaded ones), nothing relates the
/// two frames but the loops, and one loop fixes no rotation between them.
/// What no frame changes is how far: an entry e of m0's run is a candidate
/// of query q only when e's straight-line distance from m0 differs from q's
/// from q0 by at most loopAnchorRadius(q0..q, m0..e). Judged by the
/// cross-run anchor into e's run that gives e the smallest radius; true
/// when none applies (no such loop, positions or odometers missing, e in the
/// query's run) or the gate is off (odometry_anchor_m 0). Positions only:
/// metres driven would compare two passes along routes that part at a
/// junction, and refuse every true place after it.
bool withinCrossRunAnchors(const DatabaseEntry& query, const DatabaseEntry& entry,
                           const std::vector<AnchorEntries>& anchors, const IslandOptions& options);

/// Whether a recent loop places `entry` where the query is: the anchor that
/// judges it (withinLoopAnchors) has a radius of at most twice
/// odometry_anchor_m (its drift allowance no larger than the base: at 5 %
/// per metre, 6 m of driving on both sides together) and `entry` is within
/// it. False when the gate is off or no anchor applies.
bool anchoredByRecentLoop(const DatabaseEntry& query, const DatabaseEntry& entry,
                          const std::vector<AnchorEntries>& anchors, const IslandOptions& options);

/// The longest distance (m) the odometry allows between the cameras of
/// `query` and `entry` once they are taken for one place: what the gates
/// above assume of the odometry, turned into a bound on the loop's metric
/// translation. By the absolute gate, the distance between their positions
/// plus odometryGateRadius of the metres driven between them; by the
/// loop-anchored gate, the distance between the anchor's prediction and
/// `entry` (withinLoopAnchors) plus that anchor's radius; the smaller of
/// those that apply. Infinite when neither applies (a gate off, or
/// positions missing or of another odometry run). A camera mounted off the
/// odometry's origin adds up to twice its offset: the gates' radii are
/// meant to cover it.
double odometryDistanceBound(const DatabaseEntry& query, const DatabaseEntry& entry,
                             const std::vector<AnchorEntries>& anchors,
                             const IslandOptions& options);

}  // namespace bowg
