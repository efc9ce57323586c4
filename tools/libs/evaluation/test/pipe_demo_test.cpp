// End-to-end checks of the built-in demo:
//  - a SHORT rendered pipe sequence (the demo's generator with the demo's
//    options but seed 3, a sequence none of the defaults was chosen on: the
//    vocabulary was trained on seed 2, the demo preset tuned on seed 1; the
//    first revisits of the route) run through the detector with the demo's
//    parameter file and the bundled default vocabulary: the full BoWG row
//    must reach a higher recall at 100 % precision than pure bag of words
//    (the exact PR curve: one detector run per min_score), and a higher
//    recall at the preset's threshold;
//  - the real sewer frames of ../shared/data/sewer_cctv (no revisits: every
//    loop is a false positive) give zero loops at the default threshold.
// Both use the repository's own files (config/pipe.yaml, the demo's and the
// launch files' preset, and data/default_vocabulary.bowgvoc), located from
// this file's path.
#include <dirent.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "bowg/features/feature_extractor.h"
#include "bowg/parameters/parameter_table.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg_evaluation/detector_run.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/metrics.h"
#include "bowg_evaluation/parallel_runs.h"
#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/pipe_renderer.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/wall_texture.h"

namespace bowg {
namespace {

std::string repoDir() {
  // <repo>/tools/libs/evaluation/test/pipe_demo_test.cpp
  std::string f = __FILE__;
  for (int i = 0; i < 5; ++i) f = f.substr(0, f.find_last_of('/'));
  return f;
}

// The pipe preset: the demo's and the launch files' default.
std::string pipeConfig() { return repoDir() + "/config/pipe.yaml"; }
std::string defaultVocabulary() { return repoDir() + "/data/default_vocabulary.bowgvoc"; }

struct RenderedSequence {
  std::vector<eval::FrameInput> frames;
  eval::GroundTruth gt;
};

// The first `frames` frames of a sequence, rendered in memory exactly as
// `bowg_generate_pipe_sequence --seed SEED --rate 5 --marks-per-metre 8`
// renders them (the demo's options, same noise seeds).
RenderedSequence renderPipe(int frames, std::uint64_t seed, const FeatureExtractor& extractor) {
  pipe_sim::SequenceOptions so;  // the demo's options (scripts/demo.sh)
  so.seed = seed;
  so.frame_rate_hz = 5.0;
  so.max_frames = frames;
  pipe_sim::WallTextureOptions to;
  to.seed = so.seed;
  to.marks_per_metre = 8.0;
  const pipe_sim::PipeNetwork network =
      pipe_sim::PipeNetwork::figureEight(so.network_width_m, so.network_height_m);
  const pipe_sim::Route route(network, pipe_sim::defaultRouteNodes(so.laps), so.bend_radius_m);
  const std::vector<pipe_sim::FrameState> states = pipe_sim::planSequence(route, so);
  const pipe_sim::WallTexture texture(network, to);
  const pipe_sim::CameraModel camera;
  const pipe_sim::PipeRenderer renderer(network, route, texture, camera, pipe_sim::LightModel(),
                                        pipe_sim::SensorModel());
  RenderedSequence out;
  std::vector<eval::TravelPose> travel;
  for (const pipe_sim::FrameState& f : states) {
    const cv::Mat image = renderer.render(f.pose, f.exposure, so.seed * 1000003ULL + f.index);
    eval::FrameInput in;
    in.stamp = f.stamp;
    in.features = extractor.extract(image);
    in.intrinsics.valid = true;
    in.intrinsics.fx = camera.fx;
    in.intrinsics.fy = camera.fy;
    in.intrinsics.cx = camera.cx;
    in.intrinsics.cy = camera.cy;
    in.odometer = f.odometer;  // a robot's odometry: the windows in metres
    out.frames.push_back(std::move(in));
    eval::TravelPose tp;
    tp.x = f.pose.position[0];
    tp.y = f.pose.position[1];
    tp.z = f.pose.position[2];
    tp.hx = f.tangent[0];
    tp.hy = f.tangent[1];
    tp.hz = f.tangent[2];
    tp.distance = f.odometer;
    travel.push_back(tp);
  }
  out.gt = eval::groundTruthFromPoses(travel, eval::GroundTruthOptions());
  return out;
}

// Recall at 100 % precision over the exact PR curve (one detector run per
// min_score of `thresholds`) and recall/precision at the preset's min_score.
struct RowScore {
  double full_precision_recall = 0, full_precision_threshold = 0, recall = 0, precision = 0;
};

RowScore scoreRow(const std::shared_ptr<const Vocabulary>& vocabulary,
                  const PipelineOptions& pipeline, const std::string& row,
                  const RenderedSequence& seq, const std::vector<double>& thresholds) {
  const LoopDetectorOptions o = LoopDetectorOptions::ablation(row, pipeline.detector);
  const eval::DetectorRun run = eval::runDetector(vocabulary, o, seq.frames, row);
  const eval::PrPoint at = eval::operatingPoint(run, seq.gt);
  RowScore s;
  s.recall = at.recall;
  s.precision = at.precision;
  const eval::PrPoint full = eval::recallAtFullPrecision(
      eval::rerunPrCurve(vocabulary, o, seq.frames, seq.gt, thresholds, 0));
  s.full_precision_recall = full.recall;
  s.full_precision_threshold = full.threshold;
  return s;
}

// The route's first revisits start after the outer circuit (14 m, frame
// ~350 at 5 Hz): 700 frames hold the outer circuit and most of the left one.
TEST(PipeDemo, BowgBeatsPureBagOfWordsAtFullPrecisionOnAShortPipeSequence) {
  const PipelineOptions pipeline = loadParameterFile(pipeConfig());
  const auto vocabulary = std::make_shared<const Vocabulary>(loadVocabulary(defaultVocabulary()));
  const FeatureExtractor extractor(pipeline.features);
  const RenderedSequence seq = renderPipe(700, 3, extractor);
  ASSERT_GT(seq.gt.positives(), 50) << "the short sequence must contain revisits";

  // The demo's sweep around the preset's min_score (scripts/demo.sh). Pure
  // bag of words in the paper's pipeline (DBoW2 + DLoopDetector) against the
  // preset as configured.
  const std::vector<double> thresholds = {1.4, 1.3, 1.2, 1.1, 1.0, 0.8};
  const RowScore bow = scoreRow(vocabulary, pipeline, "paper_bow", seq, thresholds);
  const RowScore bowg = scoreRow(vocabulary, pipeline, "configured", seq, thresholds);
  for (const auto& r : {std::make_pair("bow ", bow), std::make_pair("bowg", bowg)}) {
    std::printf(
        "%s: R@100%%P %.3f (min_score %.2f); at min_score %.2f: recall %.3f precision %.3f\n",
        r.first, r.second.full_precision_recall, r.second.full_precision_threshold,
        pipeline.detector.islands.min_score, r.second.recall, r.second.precision);
  }
  // Strictly higher recall at 100 % precision than pure bag of words.
  // Measured: 0.888 vs 0.353 on this sequence (recall at the preset's
  // threshold 0.799 vs 0.349). The margin asserted is far below the measured.
  EXPECT_GT(bowg.full_precision_recall, bow.full_precision_recall);
  EXPECT_GT(bowg.full_precision_recall, 0.1);
  EXPECT_GT(bowg.recall, 2.0 * bow.recall);
}

std::vector<std::string> listPngs(const std::string& dir) {
  std::vector<std::string> out;
  DIR* d = ::opendir(dir.c_str());
  if (!d) return out;
  while (dirent* e = ::readdir(d)) {
    const std::string n = e->d_name;
    if (n.size() > 4 && n.compare(n.size() - 4, 4, ".png") == 0) out.push_back(dir + "/" + n);
  }
  ::closedir(d);
  std::sort(out.begin(), out.end());
  return out;
}

// Real sewer CCTV frames, one pass, no revisits: any loop is false.
TEST(PipeDemo, NoLoopOnTheSewerFramesAtTheDefaultThreshold) {
  const std::string dir = std::string(BOWG_SHARED_DATA_DIR) + "/sewer_cctv/left";
  const std::vector<std::string> files = listPngs(dir);
  if (files.empty()) GTEST_SKIP() << "no sewer frames in " << dir << " (shared data absent)";
  const PipelineOptions pipeline = loadParameterFile(pipeConfig());
  const auto vocabulary = std::make_shared<const Vocabulary>(loadVocabulary(defaultVocabulary()));
  const FeatureExtractor extractor(pipeline.features);
  std::vector<eval::FrameInput> frames;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const cv::Mat grey = cv::imread(files[i], cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(grey.empty()) << files[i];
    eval::FrameInput f;
    f.stamp = static_cast<double>(i);  // bowg_evaluate --rate 1
    f.features = extractor.extract(grey);
    frames.push_back(std::move(f));
  }
  // The preset's threshold, scores and verification, but recent_exclusion
  // for this data: the 70 frames are 7 bursts of 10 shots, not a drive; the
  // preset's 75 keyframes (3 m of driving) would never query any of them.
  // 20 excludes a frame's own burst and the next, as for a drive.
  LoopDetectorOptions options = pipeline.detector;
  options.islands.recent_exclusion = 20;
  const eval::DetectorRun run = eval::runDetector(vocabulary, options, frames, "bowg");
  int queried = 0;
  for (const eval::KeyframeRecord& k : run.keyframes) {
    if (k.status != LoopStatus::kDatabaseTooSmall) ++queried;
  }
  EXPECT_GE(queried, 40) << "the check must query most frames to mean anything";
  const std::vector<eval::Detection> loops = eval::detectionsOf(run);
  for (const eval::Detection& d : loops) {
    ADD_FAILURE() << "false loop " << d.query << " -> " << d.match << " score " << d.score;
  }
  EXPECT_TRUE(loops.empty());
}

}  // namespace
}  // namespace bowg
