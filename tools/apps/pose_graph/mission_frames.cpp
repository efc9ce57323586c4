// The missions of the pose-graph example (mission_frames.h).
#include "mission_frames.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "bowg/core/errors.h"
#include "bowg_pose_graph/mission_alignment.h"

namespace bowg {
namespace pose_graph_app {
namespace {

std::size_t missionOf(const std::vector<MissionSpan>& spans, std::size_t node) {
  for (std::size_t m = 0; m < spans.size(); ++m) {
    if (node >= spans[m].first && node < spans[m].end) return m;
  }
  return spans.size();
}

std::string label(const MissionSpan& m) {
  return "mission " + std::to_string(m.id) + " '" + m.name + "'";
}

std::vector<Eigen::Vector3d> slice(const std::vector<Eigen::Vector3d>& v, const MissionSpan& m) {
  return std::vector<Eigen::Vector3d>(v.begin() + m.first, v.begin() + m.end);
}

}  // namespace

std::vector<MissionSpan> missionSpans(const std::vector<eval::MissionStart>& starts,
                                      const std::vector<int>& frame_of_node,
                                      const std::string& source) {
  std::vector<MissionSpan> spans;
  for (const eval::MissionStart& s : starts) {
    const auto node = std::find(frame_of_node.begin(), frame_of_node.end(), s.first_frame);
    if (node == frame_of_node.end()) {
      throw FormatError(source + ": mission " + std::to_string(s.id) + " starts at frame " +
                        std::to_string(s.first_frame) + ", which the odometry does not hold");
    }
    MissionSpan span;
    span.id = s.id;
    span.name = s.name;
    span.first = static_cast<std::size_t>(node - frame_of_node.begin());
    if (!spans.empty()) spans.back().end = span.first;
    spans.push_back(span);
  }
  if (!spans.empty()) spans.back().end = frame_of_node.size();
  return spans;
}

bool sameMission(const std::vector<MissionSpan>& spans, std::size_t a, std::size_t b) {
  return missionOf(spans, a) == missionOf(spans, b);
}

pose_graph::PoseVector initialPoses(const std::vector<MissionSpan>& spans,
                                    const pose_graph::PoseVector& odometry,
                                    const std::vector<std::pair<std::size_t, std::size_t>>& loops) {
  pose_graph::PoseVector initial = odometry;
  for (std::size_t m = 1; m < spans.size(); ++m) {
    pose_graph::MissionLoopPairs pairs;
    for (const auto& l : loops) {
      // Its queries into missions already placed (ids grow with the nodes).
      if (missionOf(spans, l.first) == m && missionOf(spans, l.second) < m) {
        pairs.push_back({odometry[l.first], initial[l.second]});
      }
    }
    if (pairs.empty()) {
      throw FormatError(label(spans[m]) +
                        " has no loop into an earlier mission: nothing places its odometry frame");
    }
    const Eigen::Isometry3d world_T_mission = pose_graph::alignMission(pairs);
    for (std::size_t i = spans[m].first; i < spans[m].end; ++i) {
      initial[i] = world_T_mission * odometry[i];
    }
  }
  return initial;
}

std::string missionReport(const std::vector<MissionSpan>& spans,
                          const std::vector<Eigen::Vector3d>& truth,
                          const std::vector<Eigen::Vector3d>& odometry,
                          const std::vector<Eigen::Vector3d>& placed,
                          const std::vector<Eigen::Vector3d>& optimised,
                          const std::vector<std::pair<std::size_t, std::size_t>>& loops) {
  std::ostringstream out;
  for (std::size_t m = 1; m < spans.size(); ++m) {
    const MissionSpan& s = spans[m];
    const std::size_t across = std::count_if(loops.begin(), loops.end(), [&](const auto& l) {
      return missionOf(spans, l.first) == m && missionOf(spans, l.second) < m;
    });
    out << label(s) << ": " << (s.end - s.first) << " frames, " << across
        << " loops into earlier missions; position error against the truth\n";
    const std::vector<Eigen::Vector3d> t = slice(truth, s);
    const std::pair<const char*, const std::vector<Eigen::Vector3d>*> rows[] = {
        {"in its own odometry frame", &odometry},
        {"placed by its loops      ", &placed},
        {"pose graph + loops       ", &optimised}};
    for (const auto& row : rows) {
      const pose_graph::TrajectoryError e = pose_graph::positionError(slice(*row.second, s), t);
      char line[160];
      std::snprintf(line, sizeof line, "  %s: RMSE %.3f m, max %.3f m, at the end %.3f m\n",
                    row.first, e.rmse, e.max, e.last);
      out << line;
    }
  }
  return out.str();
}

}  // namespace pose_graph_app
}  // namespace bowg
