#include "bowg_evaluation/reference_maps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "bowg/core/bounded_file.h"
#include "bowg/database/database.h"
#include "bowg/detection/detector_merge.h"

namespace bowg {
namespace eval {

ReferenceMapSummary readReferenceMaps(const std::vector<std::string>& paths,
                                      std::shared_ptr<const Vocabulary> vocabulary,
                                      const LoopDetectorOptions& options) {
  ReferenceMapSummary summary;
  summary.bytes = std::make_shared<const std::string>(
      paths.size() == 1 ? readBoundedFile(paths.front(), FileKind::kDatabase, "database file")
                        : mergeDetectorFiles(paths, vocabulary));
  LoopDetector detector(vocabulary, options);
  detector.adopt(LoopDetector::decode(*summary.bytes, mapsSource(paths), vocabulary, options));
  const Database& db = detector.database();
  summary.entries = db.size();
  if (!db.entries().empty()) summary.last_stamp = db.entries().back().stamp;
  if (db.lastOdometer() >= 0) summary.last_odometer = db.lastOdometer();
  summary.missions = db.missions().all();
  return summary;
}

GroundTruth groundTruthAfterMaps(const GroundTruth& gt, int skipped, std::size_t map_entries) {
  const int shift = static_cast<int>(map_entries) - skipped;
  GroundTruth out;
  for (const auto& kv : gt.loops) {
    if (kv.first < skipped) continue;
    std::vector<int> matches;
    for (int m : kv.second) {
      if (m < skipped && shift != 0) {
        throw std::invalid_argument(
            "the ground truth gives frame " + std::to_string(kv.first) + " a match at frame " +
            std::to_string(m) + ", among the " + std::to_string(skipped) +
            " skipped frames, but the maps hold " + std::to_string(map_entries) +
            " keyframes: a match there is a map keyframe only when the maps are those frames");
      }
      matches.push_back(m < skipped ? m : m + shift);
    }
    out.loops[kv.first + shift] = std::move(matches);
  }
  return out;
}

void skipFrames(int skipped, std::vector<FrameInput>* frames) {
  if (skipped <= 0) return;
  if (static_cast<std::size_t>(skipped) >= frames->size()) {
    throw std::invalid_argument("--skip-frames " + std::to_string(skipped) +
                                " leaves none of the " + std::to_string(frames->size()) +
                                " frames");
  }
  // The last mission started among the skipped frames goes on.
  const FrameInput* started = nullptr;
  for (int i = 0; i < skipped; ++i) {
    if ((*frames)[i].starts_mission) started = &(*frames)[i];
  }
  FrameInput& first = (*frames)[skipped];
  if (started && !first.starts_mission) {
    first.starts_mission = true;
    first.mission_id = started->mission_id;
    first.mission_name = started->mission_name;
  }
  frames->erase(frames->begin(), frames->begin() + skipped);
}

double stampsAfterMaps(const ReferenceMapSummary& maps, double step,
                       std::vector<FrameInput>* frames) {
  if (maps.entries == 0 || frames->empty() || frames->front().stamp > maps.last_stamp) return 0;
  const double shift = maps.last_stamp + step - frames->front().stamp;
  for (FrameInput& f : *frames) f.stamp += shift;
  return shift;
}

double odometersAfterMaps(const ReferenceMapSummary& maps, std::vector<FrameInput>* frames) {
  if (!std::isfinite(maps.last_odometer)) return 0;
  const auto first = std::find_if(frames->begin(), frames->end(),
                                  [](const FrameInput& f) { return std::isfinite(f.odometer); });
  if (first == frames->end() || first->odometer > maps.last_odometer) return 0;
  const double shift = maps.last_odometer - first->odometer;
  for (FrameInput& f : *frames) f.odometer += shift;  // NaN stays NaN
  return shift;
}

}  // namespace eval
}  // namespace bowg
