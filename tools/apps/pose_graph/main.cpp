// bowg_pose_graph: the pose-graph example. Odometry and the detector's loops
// in, the optimised trajectory and its error against the truth out, so that
// one command shows what the loop closures are for (scripts/pose_graph_demo.sh).
#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"
#include "bowg_evaluation/loop_pose_file.h"
#include "bowg_evaluation/metrics.h"
#include "bowg_evaluation/text_file.h"
#include "bowg_pose_graph/camera_frames.h"
#include "bowg_pose_graph/loop_translation_error.h"
#include "bowg_pose_graph/pose_graph.h"
#include "bowg_pose_graph/trajectory_error.h"
#include "bowg_pose_graph/trajectory_file.h"
#include "bowg_pose_graph/trajectory_plot.h"
#include "mission_frames.h"
#include "pose_graph_args.h"

namespace bowg {
namespace pose_graph_app {
namespace {

std::vector<Eigen::Vector3d> positions(const std::vector<pose_graph::FramePose>& poses) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : poses) out.emplace_back(p.position[0], p.position[1], p.position[2]);
  return out;
}

std::string describe(const char* what, const pose_graph::TrajectoryError& e) {
  char line[160];
  std::snprintf(line, sizeof line, "%s: position RMSE %.3f m, max %.3f m, at the end %.3f m", what,
                e.rmse, e.max, e.last);
  return line;
}

// The metric loop edge of a loop pose, for the generator's camera (at the
// body's origin, looking along x).
pose_graph::LoopEdge metricEdge(const eval::LoopPose& p) {
  Eigen::Isometry3d q_T_m = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d R, C;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      R(r, c) = p.rotation[3 * r + c];
      C(r, c) = p.covariance[3 * r + c];
    }
  }
  q_T_m.linear() = R;
  q_T_m.translation() = Eigen::Vector3d(p.translation[0], p.translation[1], p.translation[2]);
  return pose_graph::metricLoopEdge(q_T_m, C, pose_graph::cameraAtBodyOrigin());
}

// The truth and the odometry, frame by frame, and the node of each frame.
struct Frames {
  std::vector<pose_graph::FramePose> truth, odometry;
  std::vector<std::size_t> node_of_frame;  // frame -> node, -1: none
};

Frames readFrames(const Args& a) {
  Frames f;
  f.truth = pose_graph::readTrajectory(a.truth);
  f.odometry = pose_graph::readTrajectory(a.odometry);
  if (f.truth.size() != f.odometry.size() || f.truth.empty()) {
    throw FormatError(a.odometry + ": " + std::to_string(f.odometry.size()) + " poses, " + a.truth +
                      ": " + std::to_string(f.truth.size()) + " (the same frames needed)");
  }
  for (std::size_t i = 0; i < f.truth.size(); ++i) {
    if (f.truth[i].frame != f.odometry[i].frame) {
      throw FormatError(a.odometry + ": row " + std::to_string(i + 1) + " is frame " +
                        std::to_string(f.odometry[i].frame) + ", " + a.truth + " has frame " +
                        std::to_string(f.truth[i].frame));
    }
    f.node_of_frame.resize(f.odometry[i].frame + 1, static_cast<std::size_t>(-1));
    f.node_of_frame[f.odometry[i].frame] = i;
  }
  return f;
}

// The loops with a metric translation, by (query, match).
std::map<std::pair<int, int>, eval::LoopPose> readMetricPoses(const Args& a) {
  std::map<std::pair<int, int>, eval::LoopPose> metric_poses;
  if (a.loop_poses.empty()) return metric_poses;
  for (const eval::LoopPose& p :
       eval::parseLoopPosesCsv(eval::readTextFile(a.loop_poses, "loop poses"), a.loop_poses)) {
    if (p.metric()) metric_poses[{p.query, p.match}] = p;
  }
  return metric_poses;
}

// The loops as graph edges: metric where the loop has a translation, else at
// the match's place; with the metric edges' true relative poses.
struct Loops {
  std::vector<pose_graph::LoopEdge> edges;
  std::vector<std::pair<std::size_t, std::size_t>> nodes;  // (query, match)
  std::vector<pose_graph::LoopEdge> metric_edges;
  std::vector<Eigen::Isometry3d> metric_truth;
};

Loops loopEdges(const Args& a, const Frames& f) {
  const std::vector<eval::Detection> detections =
      eval::parseDetectionsCsv(eval::readTextFile(a.loops, "loop"), a.loops);
  const std::map<std::pair<int, int>, eval::LoopPose> metric_poses = readMetricPoses(a);
  Loops out;
  for (const eval::Detection& d : detections) {
    const auto node = [&](int frame) {
      if (frame < 0 || static_cast<std::size_t>(frame) >= f.node_of_frame.size() ||
          f.node_of_frame[frame] == static_cast<std::size_t>(-1)) {
        throw FormatError(a.loops + ": loop " + std::to_string(d.query) + " -> " +
                          std::to_string(d.match) + " names frame " + std::to_string(frame) +
                          ", which " + a.odometry + " does not hold");
      }
      return f.node_of_frame[frame];
    };
    pose_graph::LoopEdge edge;
    const auto pose = metric_poses.find({d.query, d.match});
    if (pose != metric_poses.end()) {
      edge = metricEdge(pose->second);
      out.metric_edges.push_back(edge);
      out.metric_truth.push_back(f.truth[node(d.match)].isometry().inverse() *
                                 f.truth[node(d.query)].isometry());
    }
    edge.query = node(d.query);
    edge.match = node(d.match);
    out.edges.push_back(edge);
    out.nodes.emplace_back(edge.query, edge.match);
  }
  return out;
}

// The three position tracks of the report, the plot and the CSV.
struct Tracks {
  std::vector<Eigen::Vector3d> truth, odometry, optimised;
};

std::string report(const Args& a, const Tracks& t, const Loops& loops,
                   const pose_graph::SolveSummary& summary) {
  const pose_graph::TrajectoryError before = pose_graph::positionError(t.odometry, t.truth);
  const pose_graph::TrajectoryError after = pose_graph::positionError(t.optimised, t.truth);
  double driven = 0;
  for (std::size_t i = 1; i < t.truth.size(); ++i) driven += (t.truth[i] - t.truth[i - 1]).norm();
  std::ostringstream out;
  char head[160];
  std::snprintf(head, sizeof head, "%zu frames, %.1f m driven, %zu loops\n", t.truth.size(), driven,
                loops.nodes.size());
  out << head;
  if (!a.loop_poses.empty()) {
    const pose_graph::LoopTranslationError m =
        pose_graph::loopTranslationError(loops.metric_edges, loops.metric_truth);
    char line[320];
    std::snprintf(line, sizeof line,
                  "metric loops        : %zu of %zu (the rest at the match's place +- %.2f m)\n"
                  "  position error     : median %.3f m, 90 %% %.3f m (the same-place edge's: "
                  "median %.3f m, 90 %% %.3f m)\n"
                  "  truth inside the 95 %% covariance ellipsoid: %.0f %%\n",
                  m.loops, loops.nodes.size(), a.graph.loop_position_sigma, m.median, m.p90,
                  m.same_place_median, m.same_place_p90, 100 * m.inside_95);
    out << line;
  }
  out << describe("odometry only       ", before) << "\n"
      << describe("pose graph + loops  ", after) << "\n";
  char factor[96];
  std::snprintf(factor, sizeof factor, "RMSE ratio odometry / pose graph: %.2f\n",
                after.rmse > 0 ? before.rmse / after.rmse : 0.0);
  out << factor << "solver: " << summary.report << "\n";
  return out.str();
}

void writeOutputs(const std::string& dir, const Frames& f, const Tracks& t, const Loops& loops,
                  const std::string& summary) {
  ::mkdir(dir.c_str(), 0755);
  std::ostringstream csv;
  csv << "frame,truth_x,truth_y,truth_z,odometry_x,odometry_y,odometry_z,graph_x,graph_y,"
         "graph_z\n";
  csv.precision(6);
  csv << std::fixed;
  for (std::size_t i = 0; i < f.truth.size(); ++i) {
    csv << f.truth[i].frame;
    const std::vector<Eigen::Vector3d>* const tracks[] = {&t.truth, &t.odometry, &t.optimised};
    for (const std::vector<Eigen::Vector3d>* track : tracks) {
      const Eigen::Vector3d& v = (*track)[i];
      csv << "," << v.x() << "," << v.y() << "," << v.z();
    }
    csv << "\n";
  }
  writeFileAtomically(dir + "/trajectories.csv", csv.str());
  writeFileAtomically(dir + "/summary.txt", summary);
  std::vector<std::uint8_t> png;
  cv::imencode(".png", pose_graph::plotTopView(t.truth, t.odometry, t.optimised, loops.nodes), png);
  writeFileAtomically(dir + "/trajectories.png", std::string(png.begin(), png.end()));
  std::cout << "outputs in " << dir << ": trajectories.csv, summary.txt, trajectories.png\n";
}

// The surveys of --missions (one spanning every frame without it).
std::vector<MissionSpan> spansOf(const Args& a, const Frames& f) {
  std::vector<int> frame_of_node;
  for (const auto& p : f.odometry) frame_of_node.push_back(p.frame);
  std::vector<eval::MissionStart> starts{eval::MissionStart{f.odometry.front().frame, 0, ""}};
  if (!a.missions.empty()) starts = eval::readMissionStarts(a.missions);
  return missionSpans(starts, frame_of_node, a.missions);
}

int run(const Args& a) {
  const Frames f = readFrames(a);
  const Loops loops = loopEdges(a, f);
  const std::vector<MissionSpan> spans = spansOf(a, f);
  pose_graph::PoseVector odometry;
  for (const auto& p : f.odometry) odometry.push_back(p.isometry());
  const pose_graph::PoseVector initial = initialPoses(spans, odometry, loops.nodes);
  pose_graph::PoseGraph graph(a.graph);
  for (const Eigen::Isometry3d& p : initial) graph.addPose(p);
  for (std::size_t i = 1; i < odometry.size(); ++i) {
    // No odometry edge between two surveys: their frames are their own.
    if (!sameMission(spans, i - 1, i)) continue;
    graph.addOdometry(i - 1, i, odometry[i - 1].inverse() * odometry[i]);
  }
  for (const pose_graph::LoopEdge& edge : loops.edges) graph.addLoop(edge);
  const pose_graph::SolveSummary summary = graph.optimize();

  Tracks t;
  for (std::size_t i = 0; i < graph.size(); ++i) t.optimised.push_back(graph.pose(i).translation());
  t.truth = positions(f.truth);
  t.odometry = positions(f.odometry);
  std::string text = report(a, t, loops, summary);
  if (spans.size() > 1) {
    std::vector<Eigen::Vector3d> placed;
    for (const Eigen::Isometry3d& p : initial) placed.push_back(p.translation());
    text += missionReport(spans, t.truth, t.odometry, placed, t.optimised, loops.nodes);
  }
  std::cout << text;
  if (!a.output.empty()) writeOutputs(a.output, f, t, loops, text);
  return 0;
}

}  // namespace
}  // namespace pose_graph_app
}  // namespace bowg

int main(int argc, char** argv) {
  using namespace bowg::pose_graph_app;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "-h" || std::string(argv[i]) == "--help") {
      std::cout << kUsage;
      return 0;
    }
  }
  Args args;
  try {
    args = parseArgs(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n" << kUsage;
    return 2;
  }
  try {
    return run(args);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
