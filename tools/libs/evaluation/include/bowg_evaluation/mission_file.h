// The missions of a sequence for the offline evaluation (`bowg_evaluate
// --missions FILE`): a sequence of several surveys of one network (the
// generator's re-inspection sequences) is run as the robot would run them,
// each survey a mission of its own (LoopDetector::startMission), and the
// loops from a later mission into an earlier one are scored on their own.
//
// Format (the generator's missions.csv): lines `first_frame,mission_id,name`
// (the name is the rest of the line), '#' lines and blank lines ignored; the
// first mission starts at frame 0, first frames increase, ids and names are
// unique.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bowg_evaluation/detector_run.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/metrics.h"

namespace bowg {
namespace eval {

struct MissionStart {
  int first_frame = 0;
  std::uint32_t id = 0;
  std::string name;
};

/// Throws bowg::IoError when the file cannot be read, bowg::FormatError
/// ("<path>:<line>: <why>") on a malformed line or the rules above broken.
std::vector<MissionStart> readMissionStarts(const std::string& path);
/// Same, from text (`source` names it in messages).
std::vector<MissionStart> parseMissionStarts(const std::string& text, const std::string& source);

/// Marks the frames that start a mission (FrameInput::mission). Throws
/// std::invalid_argument when a mission starts beyond the last frame.
void attachMissions(const std::vector<MissionStart>& missions, std::vector<FrameInput>* frames);

/// The run's loops from a mission into another one, scored against the
/// ground truth's matches in another mission than the query's:
/// positives = queries with such a match; a loop into another mission
/// outside them is a false positive; loops within a mission are left out.
PrPoint crossMissionPoint(const DetectorRun& run, const GroundTruth& gt);

}  // namespace eval
}  // namespace bowg
