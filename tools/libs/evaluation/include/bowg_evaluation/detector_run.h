// Runs the BoWG LoopDetector over a sequence of pre-extracted keyframes, as
// fast as the CPU allows, and keeps one record per keyframe: what the
// evaluate tool prints, plots and writes. Features are extracted once by the
// caller and shared by every run (ablation rows, threshold sweep), so runs
// differ only in the detector options.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/detection/odometry_input.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/loop_pose_file.h"
#include "bowg_evaluation/metrics.h"
#include "bowg_evaluation/timing_stats.h"

namespace bowg {
namespace eval {

/// One image, ready for the detector. Every image is a keyframe: database
/// entry n is frame n (the ground truth's indexing; after reference maps of
/// M keyframes, entry M + n).
struct FrameInput {
  double stamp = 0;  ///< seconds, strictly increasing
  ImageFeatures features;
  CameraIntrinsics intrinsics;
  double feature_ms = 0;  ///< time the feature extraction took (wall clock)
  /// The process's CPU time during the extraction, every thread's: OpenCV
  /// may spread a frame's work over its own worker threads, so this, not
  /// the wall time, is what the frame costs the robot's CPU.
  double feature_cpu_ms = 0;
  /// Metres driven (odometry_file.h); NaN = unknown.
  double odometer = std::numeric_limits<double>::quiet_NaN();
  /// Position in the odometry's frame (odometry_file.h); unknown = NaN.
  OdometryPosition position;
  /// Heading in the same frame (odometry_file.h, KeyframeInput::heading);
  /// unknown = NaN.
  OdometryHeading heading;
  /// The frame starts a mission (mission_file.h): the detector starts it
  /// (LoopDetector::startMission) before processing the frame.
  bool starts_mission = false;
  /// Its id, or LoopDetector::kNextMissionId for the current or next free one.
  std::int64_t mission_id = LoopDetector::kNextMissionId;
  std::string mission_name;
};

/// The detector's input for one frame (a copy of its features).
KeyframeInput toKeyframeInput(const FrameInput& frame);

/// The per-keyframe outcome (LoopResult without the correspondences).
struct KeyframeRecord {
  int frame = 0;  ///< its database entry (the frame's index after the maps')
  double stamp = 0;
  LoopStatus status = LoopStatus::kNoFeatures;
  bool has_candidate = false;
  int candidate = -1;          ///< best candidate's frame (after islands, when any)
  double candidate_score = 0;  ///< its final score eta
  int match = -1;              ///< the loop's frame when status == kLoopDetected
  std::uint32_t mission = 0;   ///< the keyframe's mission (LoopResult::mission)
  /// The odometry it came with (LoopResult::odometry_input).
  OdometryInput odometry_input = OdometryInput::kNone;
  int correspondences = 0, inliers = 0;
  std::size_t features = 0;
  std::size_t database_size = 0;  ///< entries before this keyframe was added
  /// LoopResult::candidates_gated and candidates_gated_heading: what the
  /// odometry gates removed, and of it the heading gate's.
  std::size_t candidates_gated = 0, candidates_gated_heading = 0;
  StageTimings timings;
  double feature_ms = 0, feature_cpu_ms = 0;
  /// The loop's relative pose, when it has one (match >= 0 and intrinsics).
  bool has_pose = false;
  LoopPose pose;
};

/// Memory while the database grows: the process's resident set and the
/// engine's estimate (Database::memoryBytes()) at `keyframes` entries.
struct MemorySample {
  std::size_t keyframes = 0;
  double resident_bytes = 0;
  double estimate_bytes = 0;
};

struct DetectorRun {
  std::string name;
  LoopDetectorOptions options;
  std::vector<KeyframeRecord> keyframes;
  /// The mission of each reference-map keyframe (entries 0..; RunMaps): the
  /// records' frames follow them.
  std::vector<std::uint32_t> map_missions;
  double wall_seconds = 0;
  /// Before the first keyframe, every kMemorySampleEvery keyframes and after
  /// the last. The resident set is the process's: meaningful for a run alone
  /// in the process on a fresh heap (a later run reuses what earlier ones
  /// freed).
  std::vector<MemorySample> memory;
};
constexpr std::size_t kMemorySampleEvery = 1000;

/// Called after every keyframe with (done, total).
using ProgressCallback = std::function<void(std::size_t, std::size_t)>;

/// What a run starts from and leaves behind (reference_maps.h).
struct RunMaps {
  /// Earlier missions read into the detector before the first frame
  /// (LoopDetector::readMerged); the frames are then entries
  /// load_entries.. (KeyframeRecord::frame).
  std::vector<std::string> load;
  std::size_t load_entries = 0;
  /// Where the detector is saved after the last frame ("": nowhere).
  std::string save;
  /// The maps' bytes, read once (ReferenceMapSummary::bytes): each run
  /// decodes them (LoopDetector::decode) instead of reading and merging
  /// `load` again; `load` then only names them.
  std::shared_ptr<const std::string> bytes;
};

/// What errors call the maps at `paths`: the file, or "the merge of" them.
std::string mapsSource(const std::vector<std::string>& paths);

/// Throws what LoopDetector throws (InvalidParameter for bad options,
/// std::invalid_argument for non-increasing stamps), and std::logic_error
/// when the maps no longer hold load_entries keyframes.
DetectorRun runDetector(std::shared_ptr<const Vocabulary> vocabulary,
                        const LoopDetectorOptions& options, const std::vector<FrameInput>& frames,
                        const std::string& name, const ProgressCallback& progress = nullptr,
                        const RunMaps& maps = RunMaps());

/// The mission of entry `entry` of the run: a reference map's keyframe or a
/// frame's (std::out_of_range beyond them).
std::uint32_t missionOfEntry(const DetectorRun& run, int entry);

/// The loops a run found, scored by their final score eta.
std::vector<Detection> detectionsOf(const DetectorRun& run);

/// The relative poses of the run's loops (loop_pose_file.h).
std::vector<LoopPose> loopPosesOf(const DetectorRun& run);

/// The threshold the run's keyframes applied: min_score as the odometry most
/// of them came with raises it (islandOptionsFor; min_score for an empty run).
double appliedThreshold(const DetectorRun& run);

/// The run's operating point: every loop it found scored against `gt`, the
/// point's threshold being appliedThreshold(run) (one point of the exact PR
/// curve, whose other points are runs at other min_scores).
PrPoint operatingPoint(const DetectorRun& run, const GroundTruth& gt);

/// Per-keyframe CSV: frame,stamp,status,candidate,candidate_score,match,
/// correspondences,inliers,features,database_size,feature_ms,transform_ms,
/// word_groups_ms,query_ms,islands_ms,verification_ms,total_ms[,correct]
/// (correct = 1/0 for loops, empty otherwise; only with a ground truth).
std::string keyframesCsv(const DetectorRun& run, const GroundTruth* gt);

/// Timing statistics per stage, in pipeline order: features, transform,
/// word_groups, query, islands, verification, detector total (without
/// features), keyframe total (with features).
std::vector<std::pair<std::string, TimingStats>> stageTimingStats(const DetectorRun& run);

/// Mean and max detector time (total_ms) for database sizes in `bins`
/// equal ranges of keyframes: rows (first_size, last_size, stats).
struct TimeVsSize {
  std::size_t first = 0, last = 0;
  TimingStats total_ms;
};
std::vector<TimeVsSize> timeVersusDatabaseSize(const DetectorRun& run, int bins);

/// Growth per keyframe between the first and the last memory sample:
/// resident set and estimate (bytes per keyframe; 0 without two samples).
struct MemoryGrowth {
  std::size_t keyframes = 0;
  double resident_per_keyframe = 0, estimate_per_keyframe = 0;
};
MemoryGrowth memoryGrowth(const DetectorRun& run);

}  // namespace eval
}  // namespace bowg
