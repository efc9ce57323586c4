// The BoWG loop detector: one call per keyframe runs the whole method of the
// paper (Fig. 2): words -> word groups -> scores (word, group, distribution)
// -> normalisation -> temporal score -> islands -> temporal verification ->
// geometric verification, then adds the keyframe to the database.
//
// Not thread-safe: one thread calls process(); setOptions() may be called
// between keyframes (the nodelet serialises both with a mutex).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "bowg/core/types.h"
#include "bowg/database/missions.h"
#include "bowg/detection/detection_options.h"
#include "bowg/detection/geometric_verification.h"
#include "bowg/detection/loop_status.h"
#include "bowg/detection/metric_translation.h"
#include "bowg/detection/odometry_input.h"

namespace bowg {

class Vocabulary;
class Database;
struct DetectorState;

/// A detector file read and checked (LoopDetector::read), not yet in use: the
/// slow half of a load, kept apart so that it can run while another thread
/// keeps calling process(); LoopDetector::adopt() puts it in use.
class SavedDetector {
 public:
  SavedDetector(SavedDetector&&) noexcept;
  SavedDetector& operator=(SavedDetector&&) noexcept;
  ~SavedDetector();
  /// Keyframes in the file.
  std::size_t size() const;

 private:
  friend class LoopDetector;
  SavedDetector();
  std::shared_ptr<const Vocabulary> vocabulary_;
  std::unique_ptr<Database> database_;
  std::unique_ptr<DetectorState> state_;
};

/// Wall-clock milliseconds spent per stage for one keyframe.
struct StageTimings {
  double transform_ms = 0;     ///< descriptors -> words (+ direct index)
  double word_groups_ms = 0;   ///< word groups and refined weights
  double query_ms = 0;         ///< inverse-index scoring, normalisation, temporal
  double islands_ms = 0;       ///< islands and temporal verification
  double verification_ms = 0;  ///< geometric verification
  double total_ms = 0;
};

/// The scores of one candidate against the query (paper notation).
struct CandidateScores {
  EntryId entry = 0;
  double eta_w = 0;    ///< normalised word score (eq. 2)
  double eta_g = 0;    ///< normalised word-group score (eq. 4)
  double eta_d = 0;    ///< normalised distribution score
  double eta_sim = 0;  ///< combined similarity (eq. 5 or 9)
  double eta = 0;      ///< final score: eta_temp (eq. 7) or eta_sim
};

struct KeyframeInput {
  double stamp = 0;  ///< seconds; must increase from keyframe to keyframe
  ImageFeatures features;
  /// Optional: enables the relative pose from the essential matrix and sets
  /// the centre of the distribution fan (else the image centre).
  CameraIntrinsics intrinsics;
  /// Optional: metres driven since the first keyframe (path length of the
  /// odometry, whatever its drift: only differences of a few metres are
  /// used), never decreasing; NaN = unknown. With it the recent-exclusion
  /// window is measured in metres (IslandOptions::recent_exclusion_m).
  double odometer = std::numeric_limits<double>::quiet_NaN();
  /// Optional: the robot's position in the odometry's fixed frame, with the
  /// odometer. With both, candidates farther from the query than the
  /// odometry's drift allows are not candidates (IslandOptions::
  /// odometry_gate_m). All three finite, or all NaN (unknown).
  OdometryPosition position;
  /// Optional: the direction the robot faces in the same frame (the body's
  /// forward axis, headingFromQuaternion of the odometry's orientation).
  /// With it and the odometer, candidates the robot faced another way at
  /// are not candidates (IslandOptions::heading_gate_deg). All three finite
  /// with unit length, or all NaN (unknown).
  OdometryHeading heading;
};

struct LoopResult {
  EntryId query_id = 0;
  double stamp = 0;
  /// The mission the keyframe was added to (LoopDetector::startMission).
  std::uint32_t mission = 0;
  LoopStatus status = LoopStatus::kNoFeatures;
  /// The odometry the keyframe came with, which decided how its loop is
  /// accepted (odometry_input.h).
  OdometryInput odometry_input = OdometryInput::kNone;

  /// Best candidate before verification (valid when has_candidate).
  bool has_candidate = false;
  CandidateScores best;
  /// The mission `best` belongs to and its name (valid when has_candidate):
  /// with `status`, why a candidate of an earlier mission was refused.
  std::uint32_t best_mission = 0;
  std::string best_mission_name;
  /// Best island (valid when has_candidate).
  EntryId island_first = 0, island_last = 0;
  double island_score = 0;

  /// The loop (valid when status == kLoopDetected).
  EntryId match_id = 0;
  double match_stamp = 0;
  /// The mission the match belongs to (Database::missions()) and its name.
  std::uint32_t match_mission = 0;
  std::string match_mission_name;
  int correspondences = 0;
  int inliers = 0;
  std::vector<Correspondence> inlier_correspondences;
  /// Relative pose of the match camera in the query camera frame, from the
  /// essential matrix, when intrinsics are known: R (row-major 3x3) and the
  /// unit translation direction (scale is unobservable from two views).
  /// With the metric translation, R and the direction are the PnP fit's
  /// (metric_translation.h), which the metric translation belongs to.
  bool has_relative_pose = false;
  double rotation[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double translation_direction[3] = {0, 0, 0};
  /// The translation in metres, when the odometry gives its scale
  /// (MetricTranslationOptions; metric_status says why not otherwise): T_Q_M
  /// as above and its covariance (row-major 3x3, m^2, query optical frame).
  MetricTranslationStatus metric_status = MetricTranslationStatus::kNoOdometry;
  bool translation_scale_known = false;
  double translation_m[3] = {0, 0, 0};
  double translation_covariance[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};

  /// Normaliser scores against the previous keyframe (s(I_t, I_t-1)).
  double word_normaliser = 0, group_normaliser = 0, distribution_normaliser = 0;
  /// What the scores were divided by: the normalisers above, raised to the
  /// normaliser floor where they were unusually small (0 when not queried).
  double word_divisor = 0, group_divisor = 0, distribution_divisor = 0;
  std::size_t candidates_scored = 0;
  /// Of those, the candidates above min_score the odometry gates removed
  /// (IslandOptions::odometry_gate_m, heading_gate_deg, odometry_anchor_m),
  /// and of these the ones of another odometry run (an earlier mission)
  /// that the cross-run anchors refused (withinCrossRunAnchors), and the
  /// ones the heading gate refused where the position gate let them through
  /// (withinHeadingGate: the robot faced another way there).
  std::size_t candidates_gated = 0;
  std::size_t candidates_gated_cross_run = 0;
  std::size_t candidates_gated_heading = 0;
  StageTimings timings;
};

class LoopDetector {
 public:
  /// Throws InvalidParameter when options are invalid.
  LoopDetector(std::shared_ptr<const Vocabulary> vocabulary, const LoopDetectorOptions& options);
  ~LoopDetector();
  LoopDetector(const LoopDetector&) = delete;
  LoopDetector& operator=(const LoopDetector&) = delete;

  /// Validates, then applies from the next keyframe (database kept).
  void setOptions(const LoopDetectorOptions& options);
  const LoopDetectorOptions& options() const { return options_; }

  /// Runs the method for one keyframe and adds it to the database.
  /// Throws std::invalid_argument when the stamp does not increase or the
  /// keypoints and descriptors differ in number (the keyframe is not added).
  LoopResult process(const KeyframeInput& keyframe);

  /// The scores of every candidate of the last process() call (for
  /// evaluation and debugging), sorted by entry id.
  const std::vector<CandidateScores>& lastCandidates() const { return last_candidates_; }

  const Database& database() const { return *database_; }
  const Vocabulary& vocabulary() const { return *vocabulary_; }

  /// Atomic save (temporary file + rename) of the database and the detector
  /// state; throws IoError.
  void save(const std::string& path) const;
  /// What save() writes, without writing it: a caller that serialises
  /// process() with a lock takes the bytes under it and writes them
  /// (writeFileAtomically, atomic_file.h) after releasing it.
  std::string serialize() const;
  /// Loads a saved file: adopt(read(path, vocabulary(), options())). Throws
  /// FormatError/IoError and leaves the current state untouched on any error
  /// (other vocabulary, corrupt, truncated).
  void load(const std::string& path);
  /// Reads and checks a file written by save() for a detector of
  /// `vocabulary` and `options`, touching no detector: a caller that
  /// serialises process() with a lock reads without holding it (a large
  /// file takes seconds) and holds it for adopt() only. Throws as load().
  static SavedDetector read(const std::string& path, std::shared_ptr<const Vocabulary> vocabulary,
                            const LoopDetectorOptions& options);
  /// read() of bytes already in memory: a file's content or
  /// mergeDetectorFiles()' bytes, read once for detectors that each start on
  /// them; `source` names them in errors. Throws as load().
  static SavedDetector decode(const std::string& bytes, const std::string& source,
                              std::shared_ptr<const Vocabulary> vocabulary,
                              const LoopDetectorOptions& options);
  /// read() of several files at once: their merge (mergeDetectorFiles,
  /// detector_merge.h), every mission of each, for a detector that starts
  /// on the reference maps of earlier missions. One path: read(). Throws as
  /// read(), and std::invalid_argument when the files do not go together.
  static SavedDetector readMerged(const std::vector<std::string>& paths,
                                  std::shared_ptr<const Vocabulary> vocabulary,
                                  const LoopDetectorOptions& options);
  /// Reference maps loaded beside a running survey: the files at `paths`
  /// merged with `running`, the running detector's serialize() bytes
  /// (mergeWithRunningDetector, detector_merge.h); read without touching any
  /// detector, for adopt(). Throws as readMerged().
  static SavedDetector readMergedWithRunning(const std::vector<std::string>& paths,
                                             const std::string& running,
                                             std::shared_ptr<const Vocabulary> vocabulary);
  /// Puts a read file in use in place of the database and the memory of
  /// previous queries (cheap: no file access; the options in force now
  /// apply). Throws InvalidParameter, keeping the current state, when
  /// `saved` was read for another vocabulary.
  void adopt(SavedDetector saved);
  /// Forgets every keyframe; the current mission keeps its id and name.
  void reset();

  /// startMission's id for "the next free one".
  static constexpr std::int64_t kNextMissionId = -1;
  /// Names the mission the next keyframes belong to: the mission of that
  /// name when the database holds one (a robot continuing a survey after a
  /// restart); else the current mission, given this id and name, while it
  /// has no keyframe; else a new mission. `id`: the mission's id, unique in
  /// a network's archive (bowg_merge_databases refuses an id twice), or
  /// kNextMissionId for the current or next free one. Another mission than
  /// the current one starts a new odometry run: its positions are in a
  /// frame of their own. Throws std::invalid_argument, keeping the current
  /// mission, on an invalid name (missionNameProblem), an id outside
  /// [0, 2^32), a name held by a mission of another id or an id held by a
  /// mission of another name.
  const Mission& startMission(const std::string& name, std::int64_t id = kNextMissionId);
  /// The mission the next keyframes belong to.
  const Mission& mission() const;

 private:
  struct State;
  // A SavedDetector of the database `build` reads, decodes or merges (and
  // of the state it restores into the state it is given).
  static SavedDetector fromDatabase(
      const std::function<std::unique_ptr<Database>(DetectorState*)>& build,
      std::shared_ptr<const Vocabulary> vocabulary);
  std::shared_ptr<const Vocabulary> vocabulary_;
  LoopDetectorOptions options_;
  std::unique_ptr<Database> database_;
  std::unique_ptr<State> state_;
  std::vector<CandidateScores> last_candidates_;
};

}  // namespace bowg
