// A synthetic robot run for the pose-graph tests: two laps of a rectangle
// with the odometry of a drifting odometer (tools/apps/test).
#pragma once

#include <cmath>
#include <vector>

namespace bowg {
namespace tool_test {

/// A planar body pose (m, m, rad).
struct Pose2 {
  double x, y, yaw;
};

/// Two laps of a 20 m x 10 m rectangle in 0.2 m steps (300 frames a lap),
/// and the odometry of a robot whose odometer over-reads by 3 % and whose
/// heading drifts by 0.4 deg per metre.
inline void twoLapCircuit(std::vector<Pose2>* truth, std::vector<Pose2>* odometry) {
  const double step = 0.2;
  for (int lap = 0; lap < 2; ++lap) {
    for (int side = 0; side < 4; ++side) {
      const double length = side % 2 == 0 ? 20.0 : 10.0;
      const double yaw = side * M_PI / 2;
      for (int k = 0; k < static_cast<int>(length / step + 0.5); ++k) {
        Pose2 p = truth->empty() ? Pose2{0, 0, 0} : truth->back();
        if (!truth->empty()) {
          p.x += step * std::cos(p.yaw);
          p.y += step * std::sin(p.yaw);
        }
        p.yaw = yaw;
        truth->push_back(p);
      }
    }
  }
  odometry->push_back(truth->front());
  for (std::size_t i = 1; i < truth->size(); ++i) {
    const Pose2 &a = (*truth)[i - 1], &b = (*truth)[i];
    const double dx = b.x - a.x, dy = b.y - a.y;
    // The step in a's frame, then applied to the drifting estimate.
    const double fwd = std::cos(a.yaw) * dx + std::sin(a.yaw) * dy;
    const double left = -std::sin(a.yaw) * dx + std::cos(a.yaw) * dy;
    const Pose2 o = odometry->back();
    const double s = 1.03;
    Pose2 n;
    n.x = o.x + s * (std::cos(o.yaw) * fwd - std::sin(o.yaw) * left);
    n.y = o.y + s * (std::sin(o.yaw) * fwd + std::cos(o.yaw) * left);
    n.yaw = o.yaw + (b.yaw - a.yaw) + 0.4 * M_PI / 180 * std::hypot(dx, dy);
    odometry->push_back(n);
  }
}

}  // namespace tool_test
}  // namespace bowg
