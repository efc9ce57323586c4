// The relative pose of each loop as the detector gave it, written by
// bowg_evaluate (loop_poses_<row>.csv) and read by bowg_pose_graph, which
// turns loops with a metric translation into metric loop edges and measures
// the translations against the true poses.
//
// Format: CSV with the header
//   query,match,metric_status,r00,r01,r02,r10,r11,r12,r20,r21,r22,tx,ty,tz,
//   cxx,cxy,cxz,cyy,cyz,czz
// one row per loop with a relative pose: T_Q_M in the optical frames (a
// point X_M in the match camera is X_Q = R X_M + t, R row-major), t in
// metres when metric_status is "estimated" (metric_translation.h) and a unit
// direction otherwise; c.. the upper triangle of t's covariance (m^2, zero
// without the metric translation).
#pragma once

#include <string>
#include <vector>

namespace bowg {
namespace eval {

struct LoopPose {
  int query = 0, match = 0;
  std::string metric_status = "no_odometry";
  double rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double translation[3] = {0, 0, 0};
  double covariance[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};  ///< full 3x3, row-major
  bool metric() const { return metric_status == "estimated"; }
};

std::string loopPosesToCsv(const std::vector<LoopPose>& poses);

/// Throws bowg::FormatError "<source>:<line>: <why>" on a wrong header, a
/// missing or non-numeric cell, a rotation that is not one (|R^T R - I| >
/// 1e-6), or a metric row whose covariance is not symmetric with a positive
/// diagonal.
std::vector<LoopPose> parseLoopPosesCsv(const std::string& text, const std::string& source);

}  // namespace eval
}  // namespace bowg
