#include "bowg_evaluation/loop_pose_file.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "bowg_evaluation/csv_cells.h"

namespace bowg {
namespace eval {
namespace {

const char* const kHeader =
    "query,match,metric_status,r00,r01,r02,r10,r11,r12,r20,r21,r22,tx,ty,tz,cxx,cxy,cxz,cyy,cyz,"
    "czz";
constexpr std::size_t kColumns = 21;

}  // namespace

std::string loopPosesToCsv(const std::vector<LoopPose>& poses) {
  std::ostringstream out;
  out << kHeader << "\n" << std::setprecision(12);
  for (const LoopPose& p : poses) {
    out << p.query << "," << p.match << "," << p.metric_status;
    for (double r : p.rotation) out << "," << r;
    for (double t : p.translation) out << "," << t;
    for (int r = 0; r < 3; ++r) {
      for (int c = r; c < 3; ++c) out << "," << p.covariance[3 * r + c];
    }
    out << "\n";
  }
  return out.str();
}

std::vector<LoopPose> parseLoopPosesCsv(const std::string& text, const std::string& source) {
  CsvLines csv(text, source);
  std::vector<std::string> cells;
  if (!csv.next(&cells) || cells != splitCsv(kHeader)) {
    csv.fail(std::string("expected the header '") + kHeader + "'");
  }
  std::vector<LoopPose> out;
  while (csv.next(&cells)) {
    if (cells.size() != kColumns) {
      csv.fail("expected " + std::to_string(kColumns) + " cells, got " +
               std::to_string(cells.size()));
    }
    LoopPose p;
    double v[kColumns];
    for (std::size_t i = 0; i < kColumns; ++i) {
      if (i == 2) continue;
      if (!toDouble(cells[i], &v[i]) || !std::isfinite(v[i])) {
        csv.fail("cell " + std::to_string(i + 1) + " '" + cells[i] + "' is not a finite number");
      }
    }
    if (v[0] < 0 || v[1] < 0 || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1])) {
      csv.fail("query and match must be non-negative integers");
    }
    p.query = static_cast<int>(v[0]);
    p.match = static_cast<int>(v[1]);
    p.metric_status = cells[2];
    for (int i = 0; i < 9; ++i) p.rotation[i] = v[3 + i];
    for (int i = 0; i < 3; ++i) p.translation[i] = v[12 + i];
    int k = 15;
    for (int r = 0; r < 3; ++r) {
      for (int c = r; c < 3; ++c) p.covariance[3 * r + c] = p.covariance[3 * c + r] = v[k++];
    }
    double worst = 0;  // |R^T R - I|
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        double d = 0;
        for (int r = 0; r < 3; ++r) d += p.rotation[3 * r + a] * p.rotation[3 * r + b];
        worst = std::max(worst, std::fabs(d - (a == b ? 1.0 : 0.0)));
      }
    }
    if (worst > 1e-6) csv.fail("r00..r22 is not a rotation");
    if (p.metric() && !(p.covariance[0] > 0 && p.covariance[4] > 0 && p.covariance[8] > 0)) {
      csv.fail("a metric translation needs a covariance with a positive diagonal");
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace eval
}  // namespace bowg
