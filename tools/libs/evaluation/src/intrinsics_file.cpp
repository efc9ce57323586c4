#include "bowg_evaluation/intrinsics_file.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

#include "bowg_evaluation/csv_cells.h"
#include "bowg_evaluation/text_file.h"

namespace bowg {
namespace eval {

CameraIntrinsics parseIntrinsics(const std::string& text, const std::string& source) {
  CsvLines csv(text, source);
  std::vector<std::string> cells;
  if (!csv.next(&cells) || cells != std::vector<std::string>{"fx", "fy", "cx", "cy"}) {
    csv.fail("expected the header 'fx,fy,cx,cy'");
  }
  if (!csv.next(&cells)) csv.fail("no row after the header");
  if (cells.size() != 4) csv.fail("expected 4 cells, got " + std::to_string(cells.size()));
  double v[4];
  for (int i = 0; i < 4; ++i) {
    if (!toDouble(cells[i], &v[i]) || !std::isfinite(v[i])) {
      csv.fail("'" + cells[i] + "' is not a finite number");
    }
  }
  if (!(v[0] > 0 && v[1] > 0)) csv.fail("fx and fy must be > 0");
  if (csv.next(&cells)) csv.fail("one row expected");
  CameraIntrinsics k;
  k.valid = true;
  k.fx = v[0];
  k.fy = v[1];
  k.cx = v[2];
  k.cy = v[3];
  return k;
}

CameraIntrinsics readIntrinsics(const std::string& path) {
  return parseIntrinsics(readTextFile(path, "intrinsics"), path);
}

std::string intrinsicsToCsv(const CameraIntrinsics& k) {
  std::ostringstream out;
  out << "fx,fy,cx,cy\n"
      << std::setprecision(12) << k.fx << "," << k.fy << "," << k.cx << "," << k.cy << "\n";
  return out.str();
}

}  // namespace eval
}  // namespace bowg
