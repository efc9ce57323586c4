#include "bowg_evaluation/odometry_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "bowg/core/errors.h"
#include "bowg_evaluation/csv_cells.h"
#include "bowg_evaluation/text_file.h"

namespace bowg {
namespace eval {

std::vector<double> parseOdometry(const std::string& text, const std::string& source) {
  CsvLines csv(text, source);
  const auto fail = [&](const std::string& why) { csv.fail(why); };
  std::vector<std::string> header;
  csv.next(&header);
  int frame_col = -1, odo_col = -1, distance_col = -1, xyz[3] = {-1, -1, -1};
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "frame") frame_col = static_cast<int>(i);
    if (header[i] == "odometer") odo_col = static_cast<int>(i);
    if (header[i] == "distance") distance_col = static_cast<int>(i);
    for (int a = 0; a < 3; ++a) {
      if (header[i] == std::string(1, static_cast<char>('x' + a))) xyz[a] = static_cast<int>(i);
    }
  }
  if (odo_col < 0) odo_col = distance_col;
  // Without an odometer column, a pose file's positions: metres driven = the
  // path length through them (the drifting odometry's, with its slip).
  const bool from_positions = odo_col < 0 && xyz[0] >= 0 && xyz[1] >= 0 && xyz[2] >= 0;
  if (frame_col < 0 || (odo_col < 0 && !from_positions)) {
    fail(
        "the header needs a 'frame' column and an 'odometer' (or 'distance') column, or x, y "
        "and z");
  }
  const int last_col =
      std::max(frame_col, from_positions ? std::max(xyz[0], std::max(xyz[1], xyz[2])) : odo_col);
  std::vector<double> odometer;
  double last = -1.0, previous[3] = {0, 0, 0};
  std::vector<std::string> cells;
  while (csv.next(&cells)) {
    double frame = 0, value = 0;
    if (static_cast<int>(cells.size()) <= last_col) fail("too few columns");
    if (!toDouble(cells[frame_col], &frame) || frame < 0 || frame != std::floor(frame) ||
        frame > 1e9) {
      fail("frame '" + cells[frame_col] + "' is not a non-negative integer");
    }
    if (from_positions) {
      double p[3];
      for (int a = 0; a < 3; ++a) {
        if (!toDouble(cells[xyz[a]], &p[a]) || !std::isfinite(p[a])) {
          fail("position '" + cells[xyz[a]] + "' is not a finite number");
        }
      }
      value = last < 0 ? 0.0
                       : last + std::sqrt((p[0] - previous[0]) * (p[0] - previous[0]) +
                                          (p[1] - previous[1]) * (p[1] - previous[1]) +
                                          (p[2] - previous[2]) * (p[2] - previous[2]));
      std::copy(p, p + 3, previous);
    } else if (!toDouble(cells[odo_col], &value) || !std::isfinite(value) || value < 0) {
      fail("odometer '" + cells[odo_col] + "' is not a finite number >= 0");
    }
    if (value < last) fail("the odometer decreases (" + cells[odo_col] + " after " + std::to_string(last) + ")");
    const std::size_t f = static_cast<std::size_t>(frame);
    if (f < odometer.size()) fail("frame " + cells[frame_col] + " is not after the previous row's");
    odometer.resize(f + 1, std::numeric_limits<double>::quiet_NaN());
    odometer[f] = value;
    last = value;
  }
  return odometer;
}

std::vector<double> readOdometry(const std::string& path) {
  return parseOdometry(readTextFile(path, "odometry"), path);
}

std::vector<OdometryPosition> parseOdometryPositions(const std::string& text,
                                                     const std::string& source) {
  CsvLines csv(text, source);
  std::vector<std::string> header;
  csv.next(&header);
  int frame_col = -1, xyz[3] = {-1, -1, -1};
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "frame") frame_col = static_cast<int>(i);
    for (int a = 0; a < 3; ++a) {
      if (header[i] == std::string(1, static_cast<char>('x' + a))) xyz[a] = static_cast<int>(i);
    }
  }
  if (frame_col < 0 || xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) {
    csv.fail("the header needs 'frame', 'x', 'y' and 'z' columns");
  }
  const int last_col = std::max(frame_col, std::max(xyz[0], std::max(xyz[1], xyz[2])));
  std::vector<OdometryPosition> positions;
  std::vector<std::string> cells;
  while (csv.next(&cells)) {
    if (static_cast<int>(cells.size()) <= last_col) csv.fail("too few columns");
    double frame = 0;
    if (!toDouble(cells[frame_col], &frame) || frame < 0 || frame != std::floor(frame) ||
        frame > 1e9) {
      csv.fail("frame '" + cells[frame_col] + "' is not a non-negative integer");
    }
    double p[3];
    for (int a = 0; a < 3; ++a) {
      if (!toDouble(cells[xyz[a]], &p[a]) || !std::isfinite(p[a])) {
        csv.fail("position '" + cells[xyz[a]] + "' is not a finite number");
      }
    }
    const std::size_t f = static_cast<std::size_t>(frame);
    if (f < positions.size())
      csv.fail("frame " + cells[frame_col] + " is not after the previous row's");
    positions.resize(f + 1);
    positions[f].x = p[0];
    positions[f].y = p[1];
    positions[f].z = p[2];
  }
  return positions;
}

std::vector<OdometryPosition> readOdometryPositions(const std::string& path) {
  return parseOdometryPositions(readTextFile(path, "odometry positions"), path);
}

}  // namespace eval
}  // namespace bowg
