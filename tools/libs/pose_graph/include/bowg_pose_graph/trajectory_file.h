// Body poses per frame from CSV: the generator's poses.csv (truth) and
// odometry.csv (drifting odometry), or any file whose header names the
// columns `frame,x,y,z,qx,qy,qz,qw` (others, such as `stamp`, are ignored).
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace bowg {
namespace pose_graph {

struct FramePose {
  int frame = 0;
  double position[3] = {0, 0, 0};
  double quaternion[4] = {0, 0, 0, 1};  ///< x, y, z, w; unit length
  Eigen::Isometry3d isometry() const;
};

/// The rows in file order. Throws bowg::IoError when the file cannot be
/// read and bowg::FormatError ("<path>:<line>: <why>") on a missing column,
/// a non-numeric or non-finite value, a quaternion far from unit length
/// (|q| outside [0.9, 1.1]; closer ones are normalised) or frames that do
/// not increase.
std::vector<FramePose> readTrajectory(const std::string& path);
std::vector<FramePose> parseTrajectory(const std::string& text, const std::string& source);

}  // namespace pose_graph
}  // namespace bowg
