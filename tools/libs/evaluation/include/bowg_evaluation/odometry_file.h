// Odometers per frame for the offline evaluation (`bowg_evaluate
// --odometry FILE`): with them the detector measures its recent-exclusion
// window in metres driven (IslandOptions::recent_exclusion_m), as the nodelet
// does from its `odom` topic.
//
// Format: CSV with a header line naming the columns (the generator's
// poses.csv is one): `frame` (0-based index, rows in increasing order) and
// `odometer` (metres driven, never decreasing), or `distance` where no
// `odometer` column exists, or else `x`, `y`, `z`: a pose file (the
// generator's drifting odometry.csv), whose metres driven are the path length
// through its positions from the first row. Other columns are ignored.
//
// Odometry positions per frame (`bowg_evaluate --odometry-poses FILE`): the
// robot's dead-reckoned position in the odometry's frame, for the odometry
// gate (IslandOptions::odometry_gate_m), as the nodelet takes it from `odom`.
// Format: CSV with `frame`, `x`, `y` and `z` columns (the generator's
// drifting odometry.csv; its ground-truth poses.csv would let the gate see
// the truth). Other columns are ignored.
#pragma once

#include <string>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {
namespace eval {

/// odometer[frame]; frames the file does not list are NaN (unknown).
/// Throws bowg::IoError when the file cannot be read, bowg::FormatError
/// ("<path>:<line>: <why>") on a missing column, a non-numeric, negative or
/// decreasing odometer, or frames out of order.
std::vector<double> readOdometry(const std::string& path);
/// Same, from text (`source` names it in messages).
std::vector<double> parseOdometry(const std::string& text, const std::string& source);

/// One frame's odometry pose as the evaluator uses it: the position, and
/// the heading (the body's forward axis) where the file has an orientation.
struct OdometryPose {
  OdometryPosition position;
  OdometryHeading heading;
};

/// pose[frame] from columns frame, x, y, z and, optionally, qx, qy, qz, qw
/// (a unit quaternion: the heading); frames the file does not list are
/// unknown (NaN), and so are the headings of a file without the quaternion.
/// Throws bowg::IoError when the file cannot be read, bowg::FormatError
/// ("<path>:<line>: <why>") on a missing column, some but not all four
/// quaternion columns, a non-finite coordinate, a quaternion that is not of
/// unit length (within 0.01) or frames out of order.
std::vector<OdometryPose> readOdometryPoses(const std::string& path);
/// Same, from text (`source` names it in messages).
std::vector<OdometryPose> parseOdometryPoses(const std::string& text, const std::string& source);

}  // namespace eval
}  // namespace bowg
