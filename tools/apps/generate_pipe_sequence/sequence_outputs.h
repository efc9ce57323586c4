// Everything bowg_generate_pipe_sequence writes frame by frame: the bag
// (--bag), the PNG files, poses.csv, odometry.csv and intrinsics.csv
// (--images), missions.csv (beside both), and the driven poses the ground
// truth is computed from afterwards. The odometry is simulated here, one
// frame after the other, from the true poses; every mission starts a new
// odometry run.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bag_output.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_pipe_sim/odometry_model.h"
#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "generator_args.h"

namespace bowg {
namespace generate_pipe_sequence_app {

class SequenceOutputs {
 public:
  /// Creates the image folder (--images) and opens the bag (--bag).
  explicit SequenceOutputs(const Args& args);

  /// The frames added next belong to mission `id` named `name`, the first
  /// of them `first_frame`: a line of missions.csv, and a new odometry run
  /// with `noise` (its frame starts at the mission's first true pose). Call
  /// before the first mission's frames too.
  void startMission(int first_frame, int id, const std::string& name,
                    const pipe_sim::OdometryNoise& noise);

  /// Frame `f`, rendered as `image`, into every output; frames in order
  /// (the odometry integrates from one to the next).
  void add(const pipe_sim::FrameState& f, const cv::Mat& image);

  /// Completes the bag and writes poses.csv, odometry.csv, intrinsics.csv
  /// and missions.csv (DIR/missions.csv, <bag stem>_missions.csv).
  void finish();

  /// The poses of the frames added so far, for eval::groundTruthFromPoses.
  const std::vector<eval::TravelPose>& travel() const { return travel_; }

  /// Distance between the odometry's and the true position of the last
  /// frame added (m).
  double odometryDrift() const { return odometry_drift_m_; }

 private:
  std::string images_, bag_path_;  // --images, --bag, empty without
  pipe_sim::CameraModel camera_;
  std::unique_ptr<BagOutput> bag_;
  std::ostringstream poses_csv_, odometry_csv_, missions_csv_;
  std::vector<eval::TravelPose> travel_;
  pipe_sim::OdometrySimulator odometry_;
  double odometry_drift_m_ = 0;
};

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
