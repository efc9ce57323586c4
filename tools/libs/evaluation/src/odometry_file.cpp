#include "bowg_evaluation/odometry_file.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bowg/core/errors.h"
#include "bowg/core/odometry_heading.h"
#include "bowg_evaluation/csv_cells.h"
#include "bowg_evaluation/text_file.h"

namespace bowg {
namespace eval {
namespace {

// Column indexes of a header (-1 where absent).
struct Columns {
  int frame = -1, odometer = -1, distance = -1, xyz[3] = {-1, -1, -1};
  int quaternion[4] = {-1, -1, -1, -1};  ///< qx, qy, qz, qw
  bool hasPositions() const { return xyz[0] >= 0 && xyz[1] >= 0 && xyz[2] >= 0; }
  int quaternionColumns() const {
    return static_cast<int>(
        std::count_if(quaternion, quaternion + 4, [](int c) { return c >= 0; }));
  }
};

Columns readHeader(CsvLines* csv) {
  std::vector<std::string> header;
  csv->next(&header);
  Columns c;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const int col = static_cast<int>(i);
    if (header[i] == "frame") c.frame = col;
    if (header[i] == "odometer") c.odometer = col;
    if (header[i] == "distance") c.distance = col;
    for (int a = 0; a < 3; ++a) {
      if (header[i] == std::string(1, static_cast<char>('x' + a))) c.xyz[a] = col;
    }
    const char* const q[4] = {"qx", "qy", "qz", "qw"};
    for (int a = 0; a < 4; ++a) {
      if (header[i] == q[a]) c.quaternion[a] = col;
    }
  }
  return c;
}

// The row's frame index: a non-negative integer after the previous row's
// (`listed` frames so far).
std::size_t readFrame(const CsvLines& csv, const std::string& cell, std::size_t listed) {
  double frame = 0;
  if (!toDouble(cell, &frame) || frame < 0 || frame != std::floor(frame) || frame > 1e9) {
    csv.fail("frame '" + cell + "' is not a non-negative integer");
  }
  const std::size_t f = static_cast<std::size_t>(frame);
  if (f < listed) csv.fail("frame " + cell + " is not after the previous row's");
  return f;
}

// The row's x, y, z: finite numbers.
void readPosition(const CsvLines& csv, const std::vector<std::string>& cells, const Columns& c,
                  double p[3]) {
  for (int a = 0; a < 3; ++a) {
    if (!toDouble(cells[c.xyz[a]], &p[a]) || !std::isfinite(p[a])) {
      csv.fail("position '" + cells[c.xyz[a]] + "' is not a finite number");
    }
  }
}

// The row's heading: the forward axis of its orientation quaternion, which
// must be a unit quaternion (headingFromQuaternion's tolerance).
OdometryHeading readHeading(const CsvLines& csv, const std::vector<std::string>& cells,
                            const Columns& c) {
  double q[4];
  for (int a = 0; a < 4; ++a) {
    if (!toDouble(cells[c.quaternion[a]], &q[a])) {
      csv.fail("orientation '" + cells[c.quaternion[a]] + "' is not a number");
    }
  }
  const OdometryHeading h = headingFromQuaternion(q[0], q[1], q[2], q[3]);
  if (!h.known()) {
    csv.fail("orientation (" + cells[c.quaternion[0]] + ", " + cells[c.quaternion[1]] + ", " +
             cells[c.quaternion[2]] + ", " + cells[c.quaternion[3]] +
             ") is not a unit quaternion (qx, qy, qz, qw)");
  }
  return h;
}

}  // namespace

std::vector<double> parseOdometry(const std::string& text, const std::string& source) {
  CsvLines csv(text, source);
  const Columns c = readHeader(&csv);
  const int odo_col = c.odometer >= 0 ? c.odometer : c.distance;
  // Without an odometer column, a pose file's positions: metres driven = the
  // path length through them (the drifting odometry's, with its slip).
  const bool from_positions = odo_col < 0 && c.hasPositions();
  if (c.frame < 0 || (odo_col < 0 && !from_positions)) {
    csv.fail(
        "the header needs a 'frame' column and an 'odometer' (or 'distance') column, or x, y "
        "and z");
  }
  const int last_col = std::max(
      c.frame, from_positions ? std::max(c.xyz[0], std::max(c.xyz[1], c.xyz[2])) : odo_col);
  std::vector<double> odometer;
  double last = -1.0, previous[3] = {0, 0, 0};
  std::vector<std::string> cells;
  while (csv.next(&cells)) {
    if (static_cast<int>(cells.size()) <= last_col) csv.fail("too few columns");
    const std::size_t f = readFrame(csv, cells[c.frame], odometer.size());
    double value = 0;
    if (from_positions) {
      double p[3];
      readPosition(csv, cells, c, p);
      value = last < 0 ? 0.0
                       : last + std::sqrt((p[0] - previous[0]) * (p[0] - previous[0]) +
                                          (p[1] - previous[1]) * (p[1] - previous[1]) +
                                          (p[2] - previous[2]) * (p[2] - previous[2]));
      std::copy(p, p + 3, previous);
    } else if (!toDouble(cells[odo_col], &value) || !std::isfinite(value) || value < 0) {
      csv.fail("odometer '" + cells[odo_col] + "' is not a finite number >= 0");
    }
    if (value < last) {
      csv.fail("the odometer decreases (" + cells[odo_col] + " after " + std::to_string(last) +
               ")");
    }
    odometer.resize(f + 1, std::numeric_limits<double>::quiet_NaN());
    odometer[f] = value;
    last = value;
  }
  return odometer;
}

std::vector<double> readOdometry(const std::string& path) {
  return parseOdometry(readTextFile(path, "odometry"), path);
}

std::vector<OdometryPose> parseOdometryPoses(const std::string& text, const std::string& source) {
  CsvLines csv(text, source);
  const Columns c = readHeader(&csv);
  if (c.frame < 0 || !c.hasPositions()) {
    csv.fail("the header needs 'frame', 'x', 'y' and 'z' columns");
  }
  const int orientation = c.quaternionColumns();
  if (orientation != 0 && orientation != 4) {
    csv.fail("the header has some of 'qx', 'qy', 'qz', 'qw': an orientation needs all four");
  }
  int last_col = std::max(c.frame, *std::max_element(c.xyz, c.xyz + 3));
  if (orientation == 4)
    last_col = std::max(last_col, *std::max_element(c.quaternion, c.quaternion + 4));
  std::vector<OdometryPose> poses;
  std::vector<std::string> cells;
  while (csv.next(&cells)) {
    if (static_cast<int>(cells.size()) <= last_col) csv.fail("too few columns");
    const std::size_t f = readFrame(csv, cells[c.frame], poses.size());
    double p[3];
    readPosition(csv, cells, c, p);
    poses.resize(f + 1);
    poses[f].position.x = p[0];
    poses[f].position.y = p[1];
    poses[f].position.z = p[2];
    if (orientation == 4) poses[f].heading = readHeading(csv, cells, c);
  }
  return poses;
}

std::vector<OdometryPose> readOdometryPoses(const std::string& path) {
  return parseOdometryPoses(readTextFile(path, "odometry positions"), path);
}

}  // namespace eval
}  // namespace bowg
