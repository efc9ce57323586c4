#include "bowg_evaluation/odometry_file.h"

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
  int frame_col = -1, odo_col = -1, distance_col = -1;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "frame") frame_col = static_cast<int>(i);
    if (header[i] == "odometer") odo_col = static_cast<int>(i);
    if (header[i] == "distance") distance_col = static_cast<int>(i);
  }
  if (odo_col < 0) odo_col = distance_col;
  if (frame_col < 0 || odo_col < 0) {
    fail("the header needs a 'frame' and an 'odometer' (or 'distance') column");
  }
  std::vector<double> odometer;
  double last = -1.0;
  std::vector<std::string> cells;
  while (csv.next(&cells)) {
    double frame = 0, value = 0;
    if (static_cast<int>(cells.size()) <= std::max(frame_col, odo_col)) fail("too few columns");
    if (!toDouble(cells[frame_col], &frame) || frame < 0 || frame != std::floor(frame) ||
        frame > 1e9) {
      fail("frame '" + cells[frame_col] + "' is not a non-negative integer");
    }
    if (!toDouble(cells[odo_col], &value) || !std::isfinite(value) || value < 0) {
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

}  // namespace eval
}  // namespace bowg
