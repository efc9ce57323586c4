// LoopDetector::process: the per-keyframe pipeline of the paper (Fig. 2,
// Sec. III-B/C/D). The file format and the reading/writing live in detector_file.cpp
// (saveDetectorFile / loadDetectorFile); save() and load() wrap them.
#include "bowg/detection/loop_detector.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/detection/detector_file.h"
#include "bowg/detection/detector_merge.h"
#include "bowg/detection/geometric_verification.h"
#include "bowg/detection/islands.h"
#include "bowg/scoring/similarity.h"
#include "bowg/scoring/temporal_alignment.h"
#include "bowg/scoring/word_groups.h"
#include "bowg/vocabulary/vocabulary.h"
#include "detection/query_steps.h"

namespace bowg {
namespace {

using query_steps::Clock;
using query_steps::msBetween;

// Centre of the distribution fan (Sec. III-C): the principal point when the
// intrinsics are known, else the image centre, else (image size unknown) the
// centre of the keypoints' bounding box.
void fanCentre(const KeyframeInput& kf, double* cx, double* cy) {
  if (kf.intrinsics.valid) {
    *cx = kf.intrinsics.cx;
    *cy = kf.intrinsics.cy;
  } else if (kf.features.image_width > 0 && kf.features.image_height > 0) {
    *cx = 0.5 * kf.features.image_width;
    *cy = 0.5 * kf.features.image_height;
  } else if (!kf.features.keypoints.empty()) {
    float x0 = kf.features.keypoints[0].x, x1 = x0, y0 = kf.features.keypoints[0].y, y1 = y0;
    for (const auto& k : kf.features.keypoints) {
      x0 = std::min(x0, k.x);
      x1 = std::max(x1, k.x);
      y0 = std::min(y0, k.y);
      y1 = std::max(y1, k.y);
    }
    *cx = 0.5 * (x0 + x1);
    *cy = 0.5 * (y0 + y1);
  } else {
    *cx = *cy = 0.0;
  }
}

// What process() requires of a keyframe: as many descriptors as keypoints, a
// stamp in [0, 2^32) s after the last one, an odometer that is NaN or finite, >= 0
// and never decreasing, room in the database. Throws std::invalid_argument
// naming the field (std::length_error for a full database).
void checkKeyframe(const KeyframeInput& keyframe, const Database& database) {
  const ImageFeatures& f = keyframe.features;
  if (f.keypoints.size() != f.descriptors.size()) {
    throw std::invalid_argument("LoopDetector::process: keyframe.features has " +
                                std::to_string(f.keypoints.size()) + " keypoints but " +
                                std::to_string(f.descriptors.size()) + " descriptors");
  }
  if (database.size() >= kMaxEntries) {
    throw std::length_error("LoopDetector::process: the database holds its maximum of " +
                            std::to_string(kMaxEntries) + " keyframes");
  }
  if (!(keyframe.stamp >= 0.0 && keyframe.stamp < kStampLimit)) {
    throw std::invalid_argument("LoopDetector::process: keyframe.stamp " +
                                std::to_string(keyframe.stamp) + " s is outside [0, 2^32) s");
  }
  if (!std::isnan(keyframe.odometer)) {
    if (!std::isfinite(keyframe.odometer) || keyframe.odometer < 0.0) {
      throw std::invalid_argument(
          "LoopDetector::process: keyframe.odometer must be NaN "
          "(unknown) or finite >= 0");
    }
    const double last = database.lastOdometer();
    if (keyframe.odometer < last) {
      throw std::invalid_argument("LoopDetector::process: keyframe.odometer " +
                                  std::to_string(keyframe.odometer) + " decreases (last " +
                                  std::to_string(last) + ")");
    }
  }
  const OdometryPosition& p = keyframe.position;
  if (!p.valid()) {
    throw std::invalid_argument("LoopDetector::process: keyframe.position (" + std::to_string(p.x) +
                                ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
                                ") must be all finite or all NaN (unknown)");
  }
  const OdometryHeading& h = keyframe.heading;
  if (!h.valid()) {
    throw std::invalid_argument("LoopDetector::process: keyframe.heading (" + std::to_string(h.x) +
                                ", " + std::to_string(h.y) + ", " + std::to_string(h.z) +
                                ") must be a unit vector or all NaN (unknown)");
  }
  if (!database.empty() && !(keyframe.stamp > database.entries().back().stamp)) {
    throw std::invalid_argument("LoopDetector::process: keyframe.stamp " +
                                std::to_string(keyframe.stamp) + " does not increase (last stamp " +
                                std::to_string(database.entries().back().stamp) + ")");
  }
}

// The database options of `options` applied to `database`; only what
// depends on a changed value is rebuilt (see Database).
void applyDatabaseOptions(const LoopDetectorOptions& options, Database* database) {
  database->setScoring(options.scoring);
  database->setDirectLevel(options.geometric.direct_index_level);
  database->setFanBins(options.distribution.fan_bins);
}

}  // namespace

// The detector's memory (saved with it) and what only speeds it up.
struct LoopDetector::State : DetectorState {
  query_steps::EntryViewCache views;
  QueryScratch scratch;
};

LoopDetector::LoopDetector(std::shared_ptr<const Vocabulary> vocabulary,
                           const LoopDetectorOptions& options)
    : vocabulary_(std::move(vocabulary)), options_(options), state_(new State) {
  if (!vocabulary_ || vocabulary_->empty()) {
    throw InvalidParameter("LoopDetector: the vocabulary is null or empty");
  }
  options_.validate();
  database_.reset(new Database(vocabulary_, options_.scoring, options_.geometric.direct_index_level,
                               options_.distribution.fan_bins));
}

LoopDetector::~LoopDetector() = default;

void LoopDetector::setOptions(const LoopDetectorOptions& options) {
  options.validate();
  options_ = options;
  applyDatabaseOptions(options_, database_.get());
}

void LoopDetector::save(const std::string& path) const {
  saveDetectorFile(path, *database_, *state_);
}

std::string LoopDetector::serialize() const { return encodeDetectorFile(*database_, *state_); }

SavedDetector::SavedDetector() = default;
SavedDetector::SavedDetector(SavedDetector&&) noexcept = default;
SavedDetector& SavedDetector::operator=(SavedDetector&&) noexcept = default;
SavedDetector::~SavedDetector() = default;
std::size_t SavedDetector::size() const { return database_ ? database_->size() : 0; }

void LoopDetector::load(const std::string& path) { adopt(read(path, vocabulary_, options_)); }

SavedDetector LoopDetector::read(const std::string& path,
                                 std::shared_ptr<const Vocabulary> vocabulary,
                                 const LoopDetectorOptions& options) {
  return fromDatabase(
      [&](DetectorState* state) {
        return loadDetectorFile(path, vocabulary, options.scoring,
                                options.geometric.direct_index_level,
                                options.distribution.fan_bins, state);
      },
      vocabulary);
}

SavedDetector LoopDetector::decode(const std::string& bytes, const std::string& source,
                                   std::shared_ptr<const Vocabulary> vocabulary,
                                   const LoopDetectorOptions& options) {
  return fromDatabase(
      [&](DetectorState* state) {
        return decodeDetectorFile(bytes, source, vocabulary, options.scoring,
                                  options.geometric.direct_index_level,
                                  options.distribution.fan_bins, state);
      },
      vocabulary);
}

SavedDetector LoopDetector::readMerged(const std::vector<std::string>& paths,
                                       std::shared_ptr<const Vocabulary> vocabulary,
                                       const LoopDetectorOptions& options) {
  if (paths.size() == 1) return read(paths.front(), std::move(vocabulary), options);
  return fromDatabase(
      [&](DetectorState* state) { return mergeDetectorFiles(paths, vocabulary, state); },
      vocabulary);
}

SavedDetector LoopDetector::readMergedWithRunning(const std::vector<std::string>& paths,
                                                  const std::string& running,
                                                  std::shared_ptr<const Vocabulary> vocabulary) {
  return fromDatabase(
      [&](DetectorState* state) {
        return mergeWithRunningDetector(paths, running, vocabulary, state);
      },
      vocabulary);
}

SavedDetector LoopDetector::fromDatabase(
    const std::function<std::unique_ptr<Database>(DetectorState*)>& build,
    std::shared_ptr<const Vocabulary> vocabulary) {
  SavedDetector saved;
  saved.state_.reset(new DetectorState);
  saved.database_ = build(saved.state_.get());
  saved.vocabulary_ = std::move(vocabulary);
  return saved;
}

void LoopDetector::adopt(SavedDetector saved) {
  if (!saved.database_ || saved.vocabulary_ != vocabulary_) {
    throw InvalidParameter(
        "LoopDetector::adopt: the database was read for another vocabulary (or already adopted)");
  }
  std::unique_ptr<State> new_state(new State);
  static_cast<DetectorState&>(*new_state) = std::move(*saved.state_);
  // The loaded entries' odometry positions are in the frame of the run that
  // saved them; the keyframes that follow come from a new one.
  ++new_state->odometry_run;
  // Options changed since read() (live tuning) apply to the loaded database
  // too; unchanged ones cost nothing (see Database).
  applyDatabaseOptions(options_, saved.database_.get());
  database_.swap(saved.database_);
  state_.swap(new_state);
  last_candidates_.clear();
}

void LoopDetector::reset() {
  const Mission kept = mission();
  database_->clear();
  state_.reset(new State);
  last_candidates_.clear();
  database_->reassignMission(0, kept.id, kept.name);
  state_->mission = kept.id;
}

constexpr std::int64_t LoopDetector::kNextMissionId;

const Mission& LoopDetector::startMission(const std::string& name, std::int64_t id) {
  const std::string problem = missionNameProblem(name);
  if (!problem.empty()) throw std::invalid_argument("LoopDetector::startMission: " + problem);
  if (id < kNextMissionId || id > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("LoopDetector::startMission: mission id " + std::to_string(id) +
                                " outside 0..2^32-1 (or kNextMissionId)");
  }
  const MissionTable& table = database_->missions();
  const Mission* named = table.findByName(name);
  if (named != nullptr && id != kNextMissionId && named->id != id) {
    throw std::invalid_argument("LoopDetector::startMission: mission '" + name + "' is mission " +
                                std::to_string(named->id) + ", not " + std::to_string(id));
  }
  std::uint32_t next = state_->mission;
  if (named != nullptr) {
    next = named->id;
  } else if (mission().entries == 0) {
    // The run's mission has no keyframe yet: it becomes the one named.
    if (id != kNextMissionId) next = static_cast<std::uint32_t>(id);
    database_->reassignMission(state_->mission, next, name);
    state_->mission = next;
  } else {
    next = id != kNextMissionId ? static_cast<std::uint32_t>(id) : table.nextId();
    database_->addMission(next, name);
  }
  if (next != state_->mission && !database_->empty()) ++state_->odometry_run;
  state_->mission = next;
  return mission();
}

const Mission& LoopDetector::mission() const {
  return *database_->missions().find(state_->mission);
}

LoopResult LoopDetector::process(const KeyframeInput& keyframe) {
  const auto t0 = Clock::now();
  checkKeyframe(keyframe, *database_);
  const ImageFeatures& f = keyframe.features;

  LoopResult r;
  r.query_id = static_cast<EntryId>(database_->size());
  r.stamp = keyframe.stamp;
  r.mission = state_->mission;
  r.odometry_input = odometryInput(keyframe.odometer, keyframe.position);
  last_candidates_.clear();

  DatabaseEntry entry;
  entry.stamp = keyframe.stamp;
  entry.points = PackedPoints::fromKeypoints(f.keypoints, f.pyramid_scale_factor);
  entry.descriptors = f.descriptors;
  entry.intrinsics = keyframe.intrinsics;
  entry.odometer = keyframe.odometer;
  entry.position = keyframe.position;
  entry.heading = keyframe.heading;
  entry.odometry_run = state_->odometry_run;
  entry.mission = state_->mission;
  fanCentre(keyframe, &entry.centre_x, &entry.centre_y);

  if (f.empty()) {
    // Added anyway so that entry ids stay aligned with keyframe indices.
    database_->add(std::move(entry), database_->addToGroupTable(GroupVector()));
    query_steps::recordUnscoredQuery(options_, state_.get());
    ChainQuery unmatched;
    unmatched.query = r.query_id;
    unmatched.odometer = keyframe.odometer;
    state_->verified_chain.push(unmatched);
    r.status = LoopStatus::kNoFeatures;
    r.timings.total_ms = msBetween(t0, Clock::now());
    return r;
  }

  // 1. Words (Sec. III-A "Word Vocabulary Tree").
  BowVector bow;
  std::vector<WordId> words;
  vocabulary_->transform(f.descriptors, &bow, nullptr, 0, &words);
  entry.words = PackedWords(words);
  const auto t1 = Clock::now();
  r.timings.transform_ms = msBetween(t0, t1);

  // 2. Raw word groups, computed even when the ablation switch turns groups
  // off so that switching them on later finds every entry grouped; 3. they
  // join the table BEFORE eq. 1 is applied to the query (finite IDF for the
  // query's own groups); 4. refined weights.
  CountedGroups counted =
      database_->addToGroupTable(buildWordGroups(f.keypoints, words, options_.word_groups));
  const bool with_groups = options_.word_groups.enabled;
  const bool with_distribution = options_.distribution.enabled;
  // The entry keeps its words; the database rebuilds its BoW from them.
  const DatabaseQuery q = database_->makeQuery(std::move(bow), counted, imagePoints(f.keypoints),
                                               entry.centre_x, entry.centre_y, with_distribution);
  const auto t2 = Clock::now();
  r.timings.word_groups_ms = msBetween(t1, t2);

  // 5. Query, then the entry joins the indexes (it never matches itself).
  const IslandOptions islands = islandOptionsFor(options_.islands, r.odometry_input);
  const query_steps::QueryContext ctx{*vocabulary_,     options_,      *database_,      *state_,
                                      last_candidates_, state_->views, state_->scratch, islands};
  try {
    query_steps::runQuery(ctx, q, entry, keyframe.intrinsics, with_groups, with_distribution, &r);
  } catch (...) {
    // The raw groups are already in the table: add the entry anyway so that
    // the table, the indexes and the keyframe ids stay consistent.
    database_->add(std::move(entry), std::move(counted), q);
    throw;
  }
  // A keyframe whose loop made its place larger than indexed_per_place
  // leaves the place to the keyframes indexed before (runQuery has linked
  // it to its match).
  const int per_place = options_.islands.indexed_per_place;
  entry.searchable =
      per_place == 0 || r.status != LoopStatus::kLoopDetected ||
      state_->place_links.placeSize(r.query_id) <= static_cast<std::size_t>(per_place);
  // The query's BoW and distribution vectors are the entry's: not computed
  // twice.
  database_->add(std::move(entry), std::move(counted), q);
  r.timings.total_ms = msBetween(t0, Clock::now());
  return r;
}

}  // namespace bowg