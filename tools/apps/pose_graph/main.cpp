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

int run(const Args& a) {
  const std::vector<pose_graph::FramePose> truth = pose_graph::readTrajectory(a.truth);
  const std::vector<pose_graph::FramePose> odometry = pose_graph::readTrajectory(a.odometry);
  if (truth.size() != odometry.size() || truth.empty()) {
    throw FormatError(a.odometry + ": " + std::to_string(odometry.size()) + " poses, " + a.truth +
                      ": " + std::to_string(truth.size()) + " (the same frames needed)");
  }
  std::vector<std::size_t> node_of_frame;  // frame -> node
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i].frame != odometry[i].frame) {
      throw FormatError(a.odometry + ": row " + std::to_string(i + 1) + " is frame " +
                        std::to_string(odometry[i].frame) + ", " + a.truth + " has frame " +
                        std::to_string(truth[i].frame));
    }
    node_of_frame.resize(odometry[i].frame + 1, static_cast<std::size_t>(-1));
    node_of_frame[odometry[i].frame] = i;
  }
  const std::vector<eval::Detection> detections =
      eval::parseDetectionsCsv(eval::readTextFile(a.loops, "loop"), a.loops);

  // The loops with a metric translation, by (query, match).
  std::map<std::pair<int, int>, eval::LoopPose> metric_poses;
  if (!a.loop_poses.empty()) {
    for (const eval::LoopPose& p :
         eval::parseLoopPosesCsv(eval::readTextFile(a.loop_poses, "loop poses"), a.loop_poses)) {
      if (p.metric()) metric_poses[{p.query, p.match}] = p;
    }
  }
  std::vector<pose_graph::LoopEdge> metric_edges;
  std::vector<Eigen::Isometry3d> metric_truth;

  pose_graph::PoseGraph graph(a.graph);
  for (const auto& p : odometry) graph.addPose(p.isometry());
  for (std::size_t i = 1; i < odometry.size(); ++i) {
    graph.addOdometry(i - 1, i, odometry[i - 1].isometry().inverse() * odometry[i].isometry());
  }
  std::vector<std::pair<std::size_t, std::size_t>> loops;
  for (const eval::Detection& d : detections) {
    const auto node = [&](int frame) {
      if (frame < 0 || static_cast<std::size_t>(frame) >= node_of_frame.size() ||
          node_of_frame[frame] == static_cast<std::size_t>(-1)) {
        throw FormatError(a.loops + ": loop " + std::to_string(d.query) + " -> " +
                          std::to_string(d.match) + " names frame " + std::to_string(frame) +
                          ", which " + a.odometry + " does not hold");
      }
      return node_of_frame[frame];
    };
    pose_graph::LoopEdge edge;
    const auto pose = metric_poses.find({d.query, d.match});
    if (pose != metric_poses.end()) {
      edge = metricEdge(pose->second);
      metric_edges.push_back(edge);
      metric_truth.push_back(truth[node(d.match)].isometry().inverse() *
                             truth[node(d.query)].isometry());
    }
    edge.query = node(d.query);
    edge.match = node(d.match);
    graph.addLoop(edge);
    loops.emplace_back(edge.query, edge.match);
  }
  const pose_graph::SolveSummary summary = graph.optimize();

  std::vector<Eigen::Vector3d> optimised;
  for (std::size_t i = 0; i < graph.size(); ++i) optimised.push_back(graph.pose(i).translation());
  const std::vector<Eigen::Vector3d> true_p = positions(truth), odo_p = positions(odometry);
  const pose_graph::TrajectoryError before = pose_graph::positionError(odo_p, true_p);
  const pose_graph::TrajectoryError after = pose_graph::positionError(optimised, true_p);
  double driven = 0;
  for (std::size_t i = 1; i < true_p.size(); ++i) driven += (true_p[i] - true_p[i - 1]).norm();

  std::ostringstream report;
  char head[160];
  std::snprintf(head, sizeof head, "%zu frames, %.1f m driven, %zu loops\n", truth.size(), driven,
                loops.size());
  report << head;
  if (!a.loop_poses.empty()) {
    const pose_graph::LoopTranslationError m =
        pose_graph::loopTranslationError(metric_edges, metric_truth);
    char line[320];
    std::snprintf(line, sizeof line,
                  "metric loops        : %zu of %zu (the rest at the match's place +- %.2f m)\n"
                  "  position error     : median %.3f m, 90 %% %.3f m (the same-place edge's: "
                  "median %.3f m, 90 %% %.3f m)\n"
                  "  truth inside the 95 %% covariance ellipsoid: %.0f %%\n",
                  m.loops, loops.size(), a.graph.loop_position_sigma, m.median, m.p90,
                  m.same_place_median, m.same_place_p90, 100 * m.inside_95);
    report << line;
  }
  report << describe("odometry only       ", before) << "\n"
         << describe("pose graph + loops  ", after) << "\n";
  char factor[96];
  std::snprintf(factor, sizeof factor, "RMSE ratio odometry / pose graph: %.2f\n",
                after.rmse > 0 ? before.rmse / after.rmse : 0.0);
  report << factor << "solver: " << summary.report << "\n";
  std::cout << report.str();

  if (!a.output.empty()) {
    ::mkdir(a.output.c_str(), 0755);
    std::ostringstream csv;
    csv << "frame,truth_x,truth_y,truth_z,odometry_x,odometry_y,odometry_z,graph_x,graph_y,"
           "graph_z\n";
    csv.precision(6);
    csv << std::fixed;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      csv << truth[i].frame;
      const std::vector<Eigen::Vector3d>* const tracks[] = {&true_p, &odo_p, &optimised};
      for (const std::vector<Eigen::Vector3d>* track : tracks) {
        const Eigen::Vector3d& v = (*track)[i];
        csv << "," << v.x() << "," << v.y() << "," << v.z();
      }
      csv << "\n";
    }
    writeFileAtomically(a.output + "/trajectories.csv", csv.str());
    writeFileAtomically(a.output + "/summary.txt", report.str());
    std::vector<std::uint8_t> png;
    cv::imencode(".png", pose_graph::plotTopView(true_p, odo_p, optimised, loops), png);
    writeFileAtomically(a.output + "/trajectories.png", std::string(png.begin(), png.end()));
    std::cout << "outputs in " << a.output << ": trajectories.csv, summary.txt, trajectories.png\n";
  }
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
