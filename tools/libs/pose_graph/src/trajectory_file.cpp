#include "bowg_pose_graph/trajectory_file.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "bowg/core/errors.h"
#include "bowg_evaluation/csv_cells.h"
#include "bowg_evaluation/text_file.h"

namespace bowg {
namespace pose_graph {

Eigen::Isometry3d FramePose::isometry() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() =
      Eigen::Quaterniond(quaternion[3], quaternion[0], quaternion[1], quaternion[2]).toRotationMatrix();
  t.translation() = Eigen::Vector3d(position[0], position[1], position[2]);
  return t;
}

std::vector<FramePose> parseTrajectory(const std::string& text, const std::string& source) {
  eval::CsvLines csv(text, source);
  const auto fail = [&](const std::string& why) { csv.fail(why); };
  std::vector<std::string> header;
  csv.next(&header);
  const char* const names[8] = {"frame", "x", "y", "z", "qx", "qy", "qz", "qw"};
  int column[8];
  for (int c = 0; c < 8; ++c) {
    column[c] = -1;
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == names[c]) column[c] = static_cast<int>(i);
    }
    if (column[c] < 0) {
      fail(std::string("the header has no '") + names[c] +
           "' column (needs frame,x,y,z,qx,qy,qz,qw)");
    }
  }
  std::vector<FramePose> poses;
  std::vector<std::string> cells;
  while (csv.next(&cells)) {
    double v[8];
    for (int c = 0; c < 8; ++c) {
      if (column[c] >= static_cast<int>(cells.size())) fail("too few columns");
      if (!eval::toDouble(cells[column[c]], &v[c]) || !std::isfinite(v[c])) {
        fail(std::string(names[c]) + " '" + cells[column[c]] + "' is not a finite number");
      }
    }
    FramePose p;
    if (v[0] < 0 || v[0] != std::floor(v[0]) || v[0] > 1e9) {
      fail("frame '" + cells[column[0]] + "' is not a non-negative integer");
    }
    p.frame = static_cast<int>(v[0]);
    if (!poses.empty() && p.frame <= poses.back().frame) {
      fail("frame " + std::to_string(p.frame) + " is not after the previous row's");
    }
    const double norm = std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
    if (!(norm >= 0.9 && norm <= 1.1)) {
      fail("the quaternion has length " + std::to_string(norm) + ", not ~1");
    }
    for (int i = 0; i < 3; ++i) p.position[i] = v[1 + i];
    for (int i = 0; i < 4; ++i) p.quaternion[i] = v[4 + i] / norm;
    poses.push_back(p);
  }
  return poses;
}

std::vector<FramePose> readTrajectory(const std::string& path) {
  return parseTrajectory(eval::readTextFile(path, "trajectory"), path);
}

}  // namespace pose_graph
}  // namespace bowg
