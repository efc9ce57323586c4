// The earlier missions an offline run starts from (`bowg_evaluate --map
// FILE`, repeatable): databases saved by the nodelet, by
// bowg_merge_databases or by `bowg_evaluate --save-map`, loaded before the
// first frame as the nodelet loads ~reference_maps. Each query then searches
// them beside the live mission, and the loops into them are what a robot
// re-inspecting a network gets.
//
// Numbering: the maps' keyframes are the run's entries 0..M-1 (their ids),
// the live frames follow (entry M + i for live frame i). A ground truth
// indexes the input's frames (folder or bag order); groundTruthAfterMaps
// moves it onto the run's numbering. A re-inspection folder (the
// generator's --again) saved as a map up to its second mission's first
// frame K and run again with `--skip-frames K` keeps the folder's numbers.
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bowg/database/missions.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg_evaluation/detector_run.h"
#include "bowg_evaluation/ground_truth.h"

namespace bowg {
namespace eval {

/// What the maps hold, read once before the long feature pass.
struct ReferenceMapSummary {
  std::size_t entries = 0;  ///< keyframes: the run's entries 0..entries-1
  double last_stamp = 0;    ///< the latest keyframe's stamp (s); 0 without keyframes
  /// The metres driven of the latest keyframe with an odometer; NaN: none.
  double last_odometer = std::numeric_limits<double>::quiet_NaN();
  std::vector<Mission> missions;
  /// The maps' bytes, for the runs (RunMaps::bytes): one file's content, or
  /// the merge of several (mergeDetectorFiles). Held for the whole
  /// evaluation (the files' size in memory) so that a sweep of thresholds
  /// and rows reads and merges them once.
  std::shared_ptr<const std::string> bytes;
};

/// Reads and checks the maps as a run will (LoopDetector::decode of their
/// bytes, the same as LoopDetector::readMerged); throws what it throws,
/// naming the file.
ReferenceMapSummary readReferenceMaps(const std::vector<std::string>& paths,
                                      std::shared_ptr<const Vocabulary> vocabulary,
                                      const LoopDetectorOptions& options);

/// The ground truth of a run that skipped the input's first `skipped`
/// frames and starts on maps of `map_entries` keyframes: input frame k
/// (k >= skipped) is entry map_entries + (k - skipped). Queries among the
/// skipped frames are left out. A match among them can only be a map
/// keyframe when the map is those frames (map_entries == skipped, ids
/// kept); otherwise throws std::invalid_argument saying so.
GroundTruth groundTruthAfterMaps(const GroundTruth& gt, int skipped, std::size_t map_entries);

/// Leaves out the first `skipped` frames (after their odometry and missions
/// were attached by input index). A mission that started among them goes on
/// at the first frame kept.
void skipFrames(int skipped, std::vector<FrameInput>* frames);

/// Moves the live frames' stamps after the maps' last keyframe when they
/// are not (synthetic folder stamps n / rate start at 0 again): every stamp
/// shifted by the same amount, the first `step` seconds after the maps'.
/// Returns the shift (0 when none was needed).
double stampsAfterMaps(const ReferenceMapSummary& maps, double step,
                       std::vector<FrameInput>* frames);

/// Moves the live frames' odometers to continue from the maps' last one when
/// they start at or below it, as the nodelet's odometer continues from a
/// loaded database's (a robot's new survey counts from 0 again): every
/// odometer shifted by the same amount, the first one landing on the maps'
/// last. Returns the shift (0 when none was needed or nothing has one).
double odometersAfterMaps(const ReferenceMapSummary& maps, std::vector<FrameInput>* frames);

}  // namespace eval
}  // namespace bowg
