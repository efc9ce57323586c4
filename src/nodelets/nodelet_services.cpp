// LoopDetectorNodelet: live tuning (dynamic_reconfigure, by name through the
// parameter table), the database services (save, load, reset) and the one
// way a new run of the database starts (restartRun).
#include "bowg/core/atomic_file.h"
#include "bowg/detection/detector_file.h"
#include "bowg/detection/detector_merge.h"
#include "loop_detector_nodelet.h"

namespace bowg_ros {

dynamic_reconfigure::Config LoopDetectorNodelet::reconfigure(
    const dynamic_reconfigure::Config& requested) {
  std::lock_guard<std::mutex> lock(detector_mutex_);
  for (const std::string& m : startOnlyRequests(requested, options_)) {
    NODELET_WARN("dynamic_reconfigure: %s", m.c_str());
  }
  // Every live parameter by name through the parameter table
  // (live_parameters.h), unclamped: a value outside its range is refused.
  bowg::PipelineOptions next = options_;
  try {
    applyLiveConfig(requested, &next);
    for (const std::string& c : bowg::correctLiveParameters(vocabulary_->depth(), &next)) {
      NODELET_WARN("dynamic_reconfigure: %s", c.c_str());
    }
    detector_->setOptions(next.detector);  // validates; applies from the next keyframe
    options_ = next;
  } catch (const std::exception& e) {
    NODELET_WARN("dynamic_reconfigure: rejected (%s); keeping the previous values", e.what());
  }
  // The values in force go back to the client (corrected or kept).
  return liveConfig(options_);
}

bool LoopDetectorNodelet::saveDatabase(SaveDatabase::Request& req, SaveDatabase::Response& res) {
  const std::string path = req.path.empty() ? database_save_path_ : req.path;
  if (path.empty()) {
    res.success = false;
    res.message = "no path given and ~database_save_path is not set";
    return true;
  }
  try {
    // The bytes under the detector lock, the file (written, synced,
    // renamed) after it: a slow disk does not hold up the frames.
    std::string bytes;
    std::size_t keyframes = 0;
    {
      std::lock_guard<std::mutex> lock(detector_mutex_);
      bytes = detector_->serialize();
      keyframes = detector_->database().size();
    }
    bowg::writeFileAtomically(path, bytes);
    res.success = true;
    res.message = "saved " + std::to_string(keyframes) + " keyframes to " + path;
    NODELET_INFO("%s", res.message.c_str());
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
    NODELET_ERROR("save_database: %s", e.what());
  }
  return true;
}

bool LoopDetectorNodelet::loadDatabase(LoadDatabase::Request& req, LoadDatabase::Response& res) {
  const std::string path = req.path.empty() ? database_load_path_ : req.path;
  if (path.empty()) {
    res.success = false;
    res.message = "no path given and ~database_load_path is not set";
    return true;
  }
  bowg::LoopDetectorOptions options;
  {
    std::lock_guard<std::mutex> lock(detector_mutex_);
    options = detector_->options();
  }
  try {
    // Read and checked without the detector lock (a large file takes
    // seconds; a bad one may take its time to refuse): frames keep being
    // processed and the other services keep answering. The lock is held for
    // the swap only, which keeps the running database on any error.
    bowg::SavedDetector saved = bowg::LoopDetector::read(path, vocabulary_, options);
    std::lock_guard<std::mutex> lock(detector_mutex_);
    detector_->adopt(std::move(saved));
    restartRun(RunStart::kLoaded);  // the loaded keyframes' images are not in the file
    res.message =
        "loaded " + std::to_string(detector_->database().size()) + " keyframes from " + path;
    try {
      res.message += "; " + startMission();
    } catch (const std::invalid_argument& e) {
      // Loaded, but not into the configured mission: said, not hidden.
      res.success = false;
      res.message += "; the configured mission was refused (" + std::string(e.what()) +
                     "): keyframes continue the file's mission " +
                     std::to_string(detector_->mission().id) + " '" + detector_->mission().name +
                     "'";
      NODELET_ERROR("load_database: %s", res.message.c_str());
      return true;
    }
    res.success = true;
    NODELET_INFO("%s", res.message.c_str());
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string(e.what()) + " (the running database is kept)";
    NODELET_ERROR("load_database: %s", res.message.c_str());
  }
  return true;
}

std::string LoopDetectorNodelet::startMission() {
  const bool held = detector_->database().missions().findByName(mission_name_) != nullptr &&
                    detector_->database().missions().findByName(mission_name_)->entries > 0;
  const bowg::Mission& m = detector_->startMission(mission_name_, mission_id_);
  std::string line = "mission " + std::to_string(m.id) + " '" + m.name + "' (" +
                     (held ? "continued, " + std::to_string(m.entries) + " keyframes" : "new") +
                     "); the database holds " +
                     std::to_string(detector_->database().missions().size()) + " mission(s)";
  for (const bowg::Mission& other : detector_->database().missions().all()) {
    if (other.id == m.id) continue;
    line += ", " + std::to_string(other.id) + " '" + other.name + "' (" +
            std::to_string(other.entries) + " keyframes)";
  }
  return line;
}

bool LoopDetectorNodelet::mergeDatabases(MergeDatabases::Request& req,
                                         MergeDatabases::Response& res) {
  try {
    if (req.output.empty()) throw std::invalid_argument("no output path given");
    bowg::DetectorState state;
    const std::unique_ptr<bowg::Database> merged =
        bowg::mergeDetectorFiles(req.paths, vocabulary_, &state);
    bowg::writeFileAtomically(req.output, bowg::encodeDetectorFile(*merged, state));
    res.success = true;
    res.message = "merged " + std::to_string(req.paths.size()) + " files into " + req.output +
                  ": " + std::to_string(merged->size()) + " keyframes, " +
                  std::to_string(merged->missions().size()) + " missions";
    NODELET_INFO("merge_databases: %s", res.message.c_str());
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
    NODELET_ERROR("merge_databases: %s", res.message.c_str());
  }
  return true;
}

bool LoopDetectorNodelet::loadReferenceMaps(LoadReferenceMaps::Request& req,
                                            LoadReferenceMaps::Response& res) {
  try {
    // The running database as bytes under the lock; the maps read and
    // merged with them without it (large files take seconds). If keyframes
    // came meanwhile, the merge is made again under the lock: none is lost.
    std::string running;
    std::size_t keyframes = 0;
    {
      std::lock_guard<std::mutex> lock(detector_mutex_);
      running = detector_->serialize();
      keyframes = detector_->database().size();
    }
    bowg::SavedDetector merged =
        bowg::LoopDetector::readMergedWithRunning(req.paths, running, vocabulary_);
    std::lock_guard<std::mutex> lock(detector_mutex_);
    if (detector_->database().size() != keyframes) {
      merged =
          bowg::LoopDetector::readMergedWithRunning(req.paths, detector_->serialize(), vocabulary_);
    }
    detector_->adopt(std::move(merged));
    restartRun(RunStart::kLoaded);
    res.success = true;
    res.message = "loaded " + std::to_string(req.paths.size()) +
                  " reference map(s): " + std::to_string(detector_->database().size()) +
                  " keyframes; " + startMission();
    NODELET_INFO("load_reference_maps: %s", res.message.c_str());
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string(e.what()) + " (the running database is kept)";
    NODELET_ERROR("load_reference_maps: %s", res.message.c_str());
  }
  return true;
}

void LoopDetectorNodelet::restartRun(RunStart start) {
  if (start != RunStart::kLoaded) detector_->reset();
  debug_images_.forgetKeyframeImages();
  // After a time jump the gate began the run itself (KeyframeGate::check()).
  if (start == RunStart::kAfterTimeJump) return;
  // Stamps restart from the database's (none when empty); let the gate
  // follow (frames up to its last keyframe are skipped and counted there),
  // and its odometer continue from the database's last keyframe.
  std::lock_guard<std::mutex> gate_lock(gate_mutex_);
  gate_.reset();
  gate_.setOdometer(lastOdometer(*detector_));
  if (!detector_->database().empty()) gate_.setStampFloor(lastStamp(*detector_));
}

bool LoopDetectorNodelet::resetDatabase(std_srvs::Trigger::Request&,
                                        std_srvs::Trigger::Response& res) {
  queue_->clear();
  std::lock_guard<std::mutex> lock(detector_mutex_);
  const std::size_t n = detector_->database().size();
  restartRun(RunStart::kEmpty);
  res.success = true;
  res.message = "forgot " + std::to_string(n) + " keyframes";
  NODELET_INFO("reset: %s", res.message.c_str());
  return true;
}

}  // namespace bowg_ros
