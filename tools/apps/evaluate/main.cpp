// bowg_evaluate: runs the BoWG engine (the nodelet's code and parameter
// files) over a rosbag or an image folder as fast as the CPU allows and
// reports precision, recall, F1, the PR curve, recall at 100 % precision,
// per-stage timing and time versus database size; --ablation runs the four
// rows of the paper's ablation side by side. See docs/evaluation.md.
//
// The pieces: evaluate_args (command line), frame_loading (features of every
// frame, once), row_runs (the detector runs and PR curves), candidate_dump
// (--dump-candidates), summary_report (every output).
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/detection/odometry_input.h"
#include "bowg/parameters/parameter_table.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/mission_file.h"
#include "bowg_evaluation/reference_maps.h"
#include "candidate_dump.h"
#include "console_output.h"
#include "evaluate_args.h"
#include "frame_loading.h"
#include "row_runs.h"
#include "summary_report.h"

namespace bowg {
namespace evaluate_app {
namespace {

using namespace bowg::eval;

void makeOutputFolder(const std::string& path) {
  ::mkdir(path.c_str(), 0755);
  struct stat st;
  if (::stat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw IoError("cannot create the output folder " + path);
  }
}

// The ground truth of the frames used: queries beyond them do not count in
// the recall.
GroundTruth usedGroundTruth(const GroundTruth& gt, const Args& a, std::size_t frames) {
  if (!gt.loops.empty() && gt.loops.rbegin()->first >= static_cast<int>(frames) &&
      a.max_frames == 0) {
    std::fprintf(stderr, "warning: the ground truth names frame %d but the input has %zu frames\n",
                 gt.loops.rbegin()->first, frames);
  }
  GroundTruth used;
  for (const auto& kv : gt.loops) {
    if (kv.first < static_cast<int>(frames)) used.loops.insert(kv);
  }
  return used;
}

// The missions of the frames used: with --max-frames, those starting beyond
// them are left out.
std::vector<MissionStart> usedMissions(const Args& a, std::size_t frames) {
  std::vector<MissionStart> missions = readMissionStarts(a.missions);
  if (a.max_frames > 0) {
    missions.erase(std::remove_if(missions.begin(), missions.end(),
                                  [frames](const MissionStart& m) {
                                    return static_cast<std::size_t>(m.first_frame) >= frames;
                                  }),
                   missions.end());
  }
  return missions;
}

// The run's own mission: --mission-name, or with reference maps a new one
// named after the input (loops into the maps are then across missions).
void nameRunMission(const Args& a, std::vector<FrameInput>* frames) {
  if (!a.missions.empty() || frames->empty()) return;
  std::string name = a.mission_name;
  if (name.empty() && !a.maps.empty()) {
    std::string input = a.bag.empty() ? a.images : a.bag;
    while (input.size() > 1 && input.back() == '/') input.pop_back();
    name = input.substr(input.find_last_of('/') == std::string::npos ? 0
                                                                     : input.find_last_of('/') + 1);
  }
  if (name.empty()) return;
  FrameInput& first = frames->front();
  first.starts_mission = true;
  first.mission_name = name;
  first.mission_id = a.mission_id;
}

// The summary's line on the maps: files, keyframes, missions.
std::string describeMaps(const Args& a, const ReferenceMapSummary& maps, double stamp_shift,
                         double odometer_shift) {
  if (a.maps.empty()) return "";
  std::string line = "reference maps:";
  for (const std::string& path : a.maps) line += " " + path;
  line += " (" + std::to_string(maps.entries) + " keyframes, entries 0-" +
          std::to_string(maps.entries == 0 ? 0 : maps.entries - 1) + "; missions";
  for (const Mission& m : maps.missions) {
    line += " " + std::to_string(m.id) + " '" + m.name + "' " + std::to_string(m.entries);
  }
  line += ")";
  if (stamp_shift != 0) line += "; live stamps moved " + fmt("%.3f", stamp_shift) + " s later";
  if (odometer_shift != 0) {
    line += "; live odometers continue the maps' (+" + fmt("%.3f", odometer_shift) + " m)";
  }
  return line;
}

int run(int argc, char** argv) {
  const Args a = parseArgs(argc, argv);
  PipelineOptions pipeline;
  if (!a.config.empty()) pipeline = loadParameterFile(a.config);
  pipeline.validate();
  std::shared_ptr<const Vocabulary> vocabulary =
      std::make_shared<const Vocabulary>(loadVocabulary(a.vocabulary));
  const FeatureExtractor extractor(pipeline.features);
  const bool has_gt = !a.gt.empty();
  GroundTruth all_gt;
  if (has_gt) all_gt = readGroundTruth(a.gt);  // before the long feature pass
  if (!a.mission_name.empty() && !missionNameProblem(a.mission_name).empty()) {
    throw std::invalid_argument("--mission-name: " + missionNameProblem(a.mission_name));
  }
  ReferenceMapSummary maps;
  if (!a.maps.empty()) maps = readReferenceMaps(a.maps, vocabulary, pipeline.detector);
  makeOutputFolder(a.output);

  std::vector<FrameInput> frames = loadFrames(a, extractor);
  if (!a.odometry.empty()) attachOdometry(a.odometry, &frames);
  if (!a.odometry_poses.empty()) attachOdometryPositions(a.odometry_poses, &frames);
  if (!a.missions.empty()) attachMissions(usedMissions(a, frames.size()), &frames);
  const GroundTruth gt = groundTruthAfterMaps(usedGroundTruth(all_gt, a, frames.size()),
                                              static_cast<int>(a.skip_frames), maps.entries);
  skipFrames(static_cast<int>(a.skip_frames), &frames);
  nameRunMission(a, &frames);
  RunInputs inputs;
  inputs.frames = frames.size();
  inputs.map_entries = maps.entries;
  const double stamp_shift = stampsAfterMaps(maps, 1.0 / a.rate, &frames);
  inputs.maps = describeMaps(a, maps, stamp_shift, odometersAfterMaps(maps, &frames));
  // Which acceptance applies: what the robot of this run has.
  const OdometryInput input = odometryInputOf(frames);
  inputs.odometry = std::string("odometry: ") + describeAcceptance(input);
  // Says whether the heading gate had anything to read (an orientation
  // that is not a unit quaternion gives none).
  if (input == OdometryInput::kPositions) {
    inputs.odometry += "; a heading on " + std::to_string(framesWithHeading(frames)) + " of " +
                       std::to_string(frames.size()) + " frames";
  }
  if (!a.quiet) std::printf("%s\n", inputs.odometry.c_str());
  if (!a.dump_candidates.empty()) {
    if (!has_gt) throw std::invalid_argument("--dump-candidates needs --gt FILE");
    return dumpCandidates(a, vocabulary, pipeline.detector, frames, gt);
  }
  const double threshold = pipeline.detector.islands.min_score;
  const std::vector<double> thresholds = thresholdGrid(a.thresholds, threshold);
  const RunMaps run_maps{a.maps, maps.entries, a.save_map, maps.bytes};
  const std::vector<RowResult> results = runRows(a, vocabulary, pipeline.detector, frames,
                                                 has_gt ? &gt : nullptr, thresholds, run_maps);
  writeReport(a, results, inputs, has_gt ? &gt : nullptr, thresholds, threshold);
  return 0;
}

}  // namespace
}  // namespace evaluate_app
}  // namespace bowg

int main(int argc, char** argv) {
  try {
    return bowg::evaluate_app::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bowg_evaluate: %s\n", e.what());
    return 1;
  }
}
