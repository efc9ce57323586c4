#include "bowg_evaluation/detector_run.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "bowg/core/resident_memory.h"
#include "bowg/database/database.h"
#include "bowg/detection/islands.h"

namespace bowg {
namespace eval {

KeyframeInput toKeyframeInput(const FrameInput& frame) {
  KeyframeInput input;
  input.stamp = frame.stamp;
  input.features = frame.features;
  input.intrinsics = frame.intrinsics;
  input.odometer = frame.odometer;
  input.position = frame.position;
  input.heading = frame.heading;
  return input;
}

namespace {

// Puts the reference maps in `detector` (RunMaps: their bytes read once, or
// their files), checking they hold the keyframes counted before the run.
void startOnMaps(const RunMaps& maps, std::shared_ptr<const Vocabulary> vocabulary,
                 const LoopDetectorOptions& options, LoopDetector* detector) {
  if (maps.bytes) {
    detector->adopt(LoopDetector::decode(*maps.bytes, mapsSource(maps.load), vocabulary, options));
  } else if (!maps.load.empty()) {
    detector->adopt(LoopDetector::readMerged(maps.load, vocabulary, options));
  } else {
    return;
  }
  if (detector->database().size() != maps.load_entries) {
    throw std::logic_error("runDetector: the reference maps changed since they were counted");
  }
}

}  // namespace

std::string mapsSource(const std::vector<std::string>& paths) {
  if (paths.size() == 1) return paths.front();
  std::string source = "the merge of";
  for (std::size_t i = 0; i < paths.size(); ++i) source += (i ? ", " : " ") + paths[i];
  return source;
}

DetectorRun runDetector(std::shared_ptr<const Vocabulary> vocabulary,
                        const LoopDetectorOptions& options, const std::vector<FrameInput>& frames,
                        const std::string& name, const ProgressCallback& progress,
                        const RunMaps& maps) {
  DetectorRun run;
  run.name = name;
  run.options = options;
  LoopDetector detector(vocabulary, options);
  startOnMaps(maps, vocabulary, options, &detector);
  const std::size_t first_entry = detector.database().size();
  for (const DatabaseEntry& e : detector.database().entries())
    run.map_missions.push_back(e.mission);
  run.keyframes.reserve(frames.size());
  run.memory.reserve(frames.size() / kMemorySampleEvery + 2);
  const auto sample = [&]() {
    run.memory.push_back({detector.database().size(), residentBytes(),
                          static_cast<double>(detector.database().memoryBytes())});
  };
  sample();
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const KeyframeInput input = toKeyframeInput(frames[i]);
    KeyframeRecord k;
    k.frame = static_cast<int>(first_entry + i);
    k.stamp = frames[i].stamp;
    k.features = frames[i].features.size();
    k.feature_ms = frames[i].feature_ms;
    k.feature_cpu_ms = frames[i].feature_cpu_ms;
    k.database_size = first_entry + i;
    if (frames[i].starts_mission) {
      detector.startMission(frames[i].mission_name, frames[i].mission_id);
    }
    const LoopResult r = detector.process(input);
    k.mission = r.mission;
    k.odometry_input = r.odometry_input;
    // Entries are numbered in insertion order, and every frame is inserted
    // (also those without features), so entry id == first_entry + frame index.
    k.status = r.status;
    k.has_candidate = r.has_candidate;
    if (r.has_candidate) {
      k.candidate = static_cast<int>(r.best.entry);
      k.candidate_score = r.best.eta;
    }
    if (r.status == LoopStatus::kLoopDetected) k.match = static_cast<int>(r.match_id);
    k.correspondences = r.correspondences;
    k.candidates_gated = r.candidates_gated;
    k.candidates_gated_heading = r.candidates_gated_heading;
    k.inliers = r.inliers;
    k.timings = r.timings;
    if (r.status == LoopStatus::kLoopDetected && r.has_relative_pose) {
      k.has_pose = true;
      k.pose.query = k.frame;
      k.pose.match = k.match;
      k.pose.metric_status = toString(r.metric_status);
      std::copy(r.rotation, r.rotation + 9, k.pose.rotation);
      const double* t = r.translation_scale_known ? r.translation_m : r.translation_direction;
      std::copy(t, t + 3, k.pose.translation);
      if (r.translation_scale_known) {
        std::copy(r.translation_covariance, r.translation_covariance + 9, k.pose.covariance);
      }
    }
    run.keyframes.push_back(k);
    if (progress) progress(i + 1, frames.size());
    // Outside the timings above; memoryBytes() walks the whole database.
    if ((i + 1) % kMemorySampleEvery == 0 && i + 1 < frames.size()) sample();
  }
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!frames.empty()) sample();
  if (!maps.save.empty()) detector.save(maps.save);
  return run;
}

std::uint32_t missionOfEntry(const DetectorRun& run, int entry) {
  const std::size_t maps = run.map_missions.size();
  if (entry >= 0 && static_cast<std::size_t>(entry) < maps) return run.map_missions[entry];
  return run.keyframes.at(static_cast<std::size_t>(entry) - maps).mission;
}

std::vector<Detection> detectionsOf(const DetectorRun& run) {
  std::vector<Detection> out;
  for (const KeyframeRecord& k : run.keyframes) {
    if (k.status == LoopStatus::kLoopDetected) out.push_back({k.frame, k.match, k.candidate_score});
  }
  return out;
}

std::vector<LoopPose> loopPosesOf(const DetectorRun& run) {
  std::vector<LoopPose> out;
  for (const KeyframeRecord& k : run.keyframes) {
    if (k.has_pose) out.push_back(k.pose);
  }
  return out;
}

double appliedThreshold(const DetectorRun& run) {
  std::array<std::size_t, kOdometryInputs> count{};
  for (const KeyframeRecord& k : run.keyframes) ++count[static_cast<std::size_t>(k.odometry_input)];
  const auto most = std::max_element(count.begin(), count.end());
  const OdometryInput input = run.keyframes.empty()
                                  ? OdometryInput::kPositions
                                  : static_cast<OdometryInput>(most - count.begin());
  return islandOptionsFor(run.options.islands, input).min_score;
}

PrPoint operatingPoint(const DetectorRun& run, const GroundTruth& gt) {
  // Every loop counts: the threshold already acted inside the detector.
  PrPoint p = evaluateAt(detectionsOf(run), gt, -std::numeric_limits<double>::infinity());
  p.threshold = appliedThreshold(run);
  return p;
}

std::string keyframesCsv(const DetectorRun& run, const GroundTruth* gt) {
  std::ostringstream out;
  out << "frame,stamp,status,candidate,candidate_score,match,correspondences,inliers,features,"
         "database_size,candidates_gated,candidates_gated_heading,feature_ms,transform_ms,"
         "word_groups_ms,query_ms,islands_ms,verification_ms,total_ms"
      << (gt ? ",correct" : "") << "\n";
  for (const KeyframeRecord& k : run.keyframes) {
    out << k.frame << "," << std::fixed << std::setprecision(6) << k.stamp << ","
        << toString(k.status) << ",";
    if (k.has_candidate)
      out << k.candidate << "," << k.candidate_score;
    else
      out << ",";
    out << "," << (k.match >= 0 ? std::to_string(k.match) : "") << "," << k.correspondences << ","
        << k.inliers << "," << k.features << "," << k.database_size << "," << k.candidates_gated
        << "," << k.candidates_gated_heading << std::setprecision(3) << "," << k.feature_ms << ","
        << k.timings.transform_ms << "," << k.timings.word_groups_ms << "," << k.timings.query_ms
        << "," << k.timings.islands_ms << "," << k.timings.verification_ms << ","
        << k.timings.total_ms;
    if (gt) {
      out << ",";
      if (k.match >= 0) out << (gt->contains(k.frame, k.match) ? 1 : 0);
    }
    out << "\n";
  }
  return out.str();
}

std::vector<std::pair<std::string, TimingStats>> stageTimingStats(const DetectorRun& run) {
  constexpr int kStages = 9;
  const char* names[kStages] = {"features",       "transform",      "word_groups",
                                "query",          "islands",        "verification",
                                "detector_total", "keyframe_total", "features_cpu"};
  std::vector<std::vector<double>> values(kStages);
  for (const KeyframeRecord& k : run.keyframes) {
    const StageTimings& t = k.timings;
    const double v[kStages] = {
        k.feature_ms,      t.transform_ms, t.word_groups_ms,          t.query_ms,      t.islands_ms,
        t.verification_ms, t.total_ms,     k.feature_ms + t.total_ms, k.feature_cpu_ms};
    for (int i = 0; i < kStages; ++i) values[i].push_back(v[i]);
  }
  std::vector<std::pair<std::string, TimingStats>> out;
  for (int i = 0; i < kStages; ++i) out.emplace_back(names[i], computeTimingStats(values[i]));
  return out;
}

std::vector<TimeVsSize> timeVersusDatabaseSize(const DetectorRun& run, int bins) {
  std::vector<TimeVsSize> out;
  const std::size_t n = run.keyframes.size();
  if (n == 0 || bins < 1) return out;
  const std::size_t per_bin = std::max<std::size_t>(1, (n + bins - 1) / bins);
  for (std::size_t first = 0; first < n; first += per_bin) {
    const std::size_t last = std::min(n, first + per_bin) - 1;
    std::vector<double> v;
    for (std::size_t i = first; i <= last; ++i) v.push_back(run.keyframes[i].timings.total_ms);
    TimeVsSize row;
    row.first = run.keyframes[first].database_size;
    row.last = run.keyframes[last].database_size;
    row.total_ms = computeTimingStats(v);
    out.push_back(row);
  }
  return out;
}

MemoryGrowth memoryGrowth(const DetectorRun& run) {
  MemoryGrowth g;
  if (run.memory.size() < 2) return g;
  const MemorySample& a = run.memory.front();
  const MemorySample& b = run.memory.back();
  g.keyframes = b.keyframes - a.keyframes;
  if (g.keyframes == 0) return g;
  g.resident_per_keyframe = (b.resident_bytes - a.resident_bytes) / g.keyframes;
  g.estimate_per_keyframe = (b.estimate_bytes - a.estimate_bytes) / g.keyframes;
  return g;
}

}  // namespace eval
}  // namespace bowg
