// Everything bowg_generate_pipe_sequence writes frame by frame: the bag
// (--bag), the PNG files and poses.csv (--images), and the driven poses the
// ground truth is computed from afterwards.
#pragma once

#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bag_output.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "generator_args.h"

namespace bowg {
namespace generate_pipe_sequence_app {

class SequenceOutputs {
 public:
  /// Creates the image folder (--images) and opens the bag (--bag).
  explicit SequenceOutputs(const Args& args);

  /// Frame `f`, rendered as `image`, into every output.
  void add(const pipe_sim::FrameState& f, const cv::Mat& image);

  /// Completes the bag and writes poses.csv.
  void finish();

  /// The poses of the frames added so far, for eval::groundTruthFromPoses.
  const std::vector<eval::TravelPose>& travel() const { return travel_; }

 private:
  std::string images_;  // --images, empty without
  std::unique_ptr<BagOutput> bag_;
  std::ostringstream poses_csv_;
  std::vector<eval::TravelPose> travel_;
};

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
