#include "bowg/detection/odometry_gate.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bowg/core/odometry_heading.h"

namespace bowg {
namespace {

// Whether `e` has a position and an odometer of odometry run `run`.
bool placed(const DatabaseEntry& e, std::uint32_t run) {
  return e.position.known() && e.odometry_run == run && std::isfinite(e.odometer);
}

double squaredNorm(double dx, double dy, double dz) { return dx * dx + dy * dy + dz * dz; }

// Whether the four entries carry positions and odometers of the query's run.
bool anchorApplies(const DatabaseEntry& query, const DatabaseEntry& entry,
                   const DatabaseEntry& anchor_query, const DatabaseEntry& anchor_match) {
  const std::uint32_t run = query.odometry_run;
  return placed(query, run) && placed(entry, run) && placed(anchor_query, run) &&
         placed(anchor_match, run);
}

double anchorRadius(const DatabaseEntry& query, const DatabaseEntry& entry,
                    const DatabaseEntry& anchor_query, const DatabaseEntry& anchor_match,
                    const IslandOptions& options) {
  return loopAnchorRadius(options, query.odometer - anchor_query.odometer,
                          entry.odometer - anchor_match.odometer);
}

// The squared distance between where the anchor predicts `entry` (query
// moved from anchor_query as entry moved from anchor_match) and `entry`.
double anchoredOffsetSquared(const DatabaseEntry& query, const DatabaseEntry& entry,
                             const DatabaseEntry& anchor_query, const DatabaseEntry& anchor_match) {
  const OdometryPosition& q = query.position;
  const OdometryPosition& e = entry.position;
  const OdometryPosition& q0 = anchor_query.position;
  const OdometryPosition& m0 = anchor_match.position;
  return squaredNorm((q.x - q0.x) - (e.x - m0.x), (q.y - q0.y) - (e.y - m0.y),
                     (q.z - q0.z) - (e.z - m0.z));
}

// The loop said anchor_query and anchor_match are one place: entry is where
// query is when it moved from anchor_match as query moved from anchor_query.
bool anchoredWithin(const DatabaseEntry& query, const DatabaseEntry& entry,
                    const DatabaseEntry& anchor_query, const DatabaseEntry& anchor_match,
                    double radius) {
  return anchoredOffsetSquared(query, entry, anchor_query, anchor_match) <= radius * radius;
}

// The squared distance between two entries' positions.
double positionDistanceSquared(const DatabaseEntry& a, const DatabaseEntry& b) {
  return squaredNorm(a.position.x - b.position.x, a.position.y - b.position.y,
                     a.position.z - b.position.z);
}

// The anchor that judges `entry` (the smallest radius among those that
// `applies` to it) and its radius; nullptr when none applies.
template <typename Applies>
const AnchorEntries* bestAnchorWhere(const DatabaseEntry& query, const DatabaseEntry& entry,
                                     const std::vector<AnchorEntries>& anchors,
                                     const IslandOptions& options, Applies applies,
                                     double* radius) {
  const AnchorEntries* best = nullptr;
  for (const AnchorEntries& a : anchors) {
    if (!applies(query, entry, *a.query, *a.match)) continue;
    const double r = anchorRadius(query, entry, *a.query, *a.match, options);
    if (best == nullptr || r < *radius) {
      best = &a;
      *radius = r;
    }
  }
  return best;
}

// The loop-anchored gate's anchor of `entry` within the query's run.
const AnchorEntries* bestAnchor(const DatabaseEntry& query, const DatabaseEntry& entry,
                                const std::vector<AnchorEntries>& anchors,
                                const IslandOptions& options, double* radius) {
  return bestAnchorWhere(query, entry, anchors, options, anchorApplies, radius);
}

// Whether anchor (aq, am) ties the query's run to `entry`'s, another one,
// with the positions and odometers the cross-run gate needs.
bool crossAnchorApplies(const DatabaseEntry& query, const DatabaseEntry& entry,
                        const DatabaseEntry& aq, const DatabaseEntry& am) {
  return entry.odometry_run != query.odometry_run && placed(query, query.odometry_run) &&
         placed(aq, query.odometry_run) && placed(entry, entry.odometry_run) &&
         placed(am, entry.odometry_run);
}

// How much farther (or nearer) the entry lies from the anchor's match than
// the query from the anchor's query, in straight lines: no rotation needed.
double crossRunMismatch(const DatabaseEntry& query, const DatabaseEntry& entry,
                        const DatabaseEntry& aq, const DatabaseEntry& am) {
  return std::fabs(std::sqrt(positionDistanceSquared(query, aq)) -
                   std::sqrt(positionDistanceSquared(entry, am)));
}

}  // namespace

double odometryGateRadius(const IslandOptions& options, double driven_m) {
  return options.odometry_gate_m + options.odometry_gate_drift * std::fabs(driven_m);
}

bool odometryGateApplies(const DatabaseEntry& query, const DatabaseEntry& entry,
                         const IslandOptions& options) {
  return options.odometry_gate_m > 0.0 && placed(query, query.odometry_run) &&
         placed(entry, query.odometry_run);
}

bool withinOdometryGate(const DatabaseEntry& query, const DatabaseEntry& entry,
                        const IslandOptions& options) {
  if (!odometryGateApplies(query, entry, options)) return true;
  const double radius = odometryGateRadius(options, query.odometer - entry.odometer);
  return positionDistanceSquared(query, entry) <= radius * radius;
}

double headingGateBound(const IslandOptions& options, double driven_m) {
  return options.heading_gate_deg + options.heading_gate_drift_deg * std::sqrt(std::fabs(driven_m));
}

bool withinHeadingGate(const DatabaseEntry& query, const DatabaseEntry& entry,
                       const IslandOptions& options) {
  if (!(options.heading_gate_deg > 0.0)) return true;
  const auto headed = [&](const DatabaseEntry& e) {
    return e.heading.known() && std::isfinite(e.odometer) && e.odometry_run == query.odometry_run;
  };
  if (!headed(query) || !headed(entry)) return true;
  return headingAngleDeg(query.heading, entry.heading) <=
         headingGateBound(options, query.odometer - entry.odometer);
}

double loopAnchorRadius(const IslandOptions& options, double query_driven_m,
                        double entry_driven_m) {
  return options.odometry_anchor_m +
         options.odometry_gate_drift * (std::fabs(query_driven_m) + std::fabs(entry_driven_m));
}

bool withinLoopAnchors(const DatabaseEntry& query, const DatabaseEntry& entry,
                       const std::vector<AnchorEntries>& anchors, const IslandOptions& options) {
  if (!(options.odometry_anchor_m > 0.0)) return true;
  double radius = 0.0;
  const AnchorEntries* best = bestAnchor(query, entry, anchors, options, &radius);
  return best == nullptr || anchoredWithin(query, entry, *best->query, *best->match, radius);
}

bool withinCrossRunAnchors(const DatabaseEntry& query, const DatabaseEntry& entry,
                           const std::vector<AnchorEntries>& anchors,
                           const IslandOptions& options) {
  if (!(options.odometry_anchor_m > 0.0)) return true;
  double radius = 0.0;
  const AnchorEntries* best =
      bestAnchorWhere(query, entry, anchors, options, crossAnchorApplies, &radius);
  return best == nullptr || crossRunMismatch(query, entry, *best->query, *best->match) <= radius;
}

bool anchoredByRecentLoop(const DatabaseEntry& query, const DatabaseEntry& entry,
                          const std::vector<AnchorEntries>& anchors, const IslandOptions& options) {
  if (!(options.odometry_anchor_m > 0.0)) return false;
  double radius = 0.0;
  const AnchorEntries* best = bestAnchor(query, entry, anchors, options, &radius);
  return best != nullptr && radius <= 2.0 * options.odometry_anchor_m &&
         anchoredWithin(query, entry, *best->query, *best->match, radius);
}

double odometryDistanceBound(const DatabaseEntry& query, const DatabaseEntry& entry,
                             const std::vector<AnchorEntries>& anchors,
                             const IslandOptions& options) {
  double bound = std::numeric_limits<double>::infinity();
  const std::uint32_t run = query.odometry_run;
  if (options.odometry_gate_m > 0.0 && placed(query, run) && placed(entry, run)) {
    bound = std::sqrt(positionDistanceSquared(query, entry)) +
            odometryGateRadius(options, query.odometer - entry.odometer);
  }
  if (options.odometry_anchor_m > 0.0) {
    double radius = 0.0;
    const AnchorEntries* best = bestAnchor(query, entry, anchors, options, &radius);
    if (best != nullptr) {
      bound = std::min(
          bound,
          std::sqrt(anchoredOffsetSquared(query, entry, *best->query, *best->match)) + radius);
    }
  }
  return bound;
}

}  // namespace bowg
