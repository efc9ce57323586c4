// The nodelet's "loop detector" diagnostics: counters of what happened to the
// frames and keyframes, and the status built from them (level, message,
// values). Every event and diagnose() take the class's own lock, so the
// camera callbacks, the worker and the diagnostics timer call it as they
// are, holding no lock of its. It takes no other lock, so a caller may hold
// any of its own. No ROS master needed: it only fills a
// diagnostic_updater::DiagnosticStatusWrapper.
#pragma once

#include <diagnostic_updater/DiagnosticStatusWrapper.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "bowg/detection/loop_detector.h"
#include "bowg/features/image_check.h"
#include "bowg_ros/keyframe_gate.h"

namespace bowg_ros {

/// What the warnings name and how long they last: the nodelet's input mode
/// and its topics as it resolved them.
struct DiagnosticsSettings {
  enum class Input { kImage, kCompressed, kFeatures };
  Input input = Input::kImage;
  std::string image_topic;     ///< the image topic (compressed: without "/compressed")
  std::string features_topic;  ///< keyframe_features
  std::string camera_info_topic, odom_topic, odometer_topic, odometer_stamped_topic;
  double window = 30.0;        ///< s: how long a condition stays in the status
  bool distance_gate = false;  ///< ~min_keyframe_distance > 0
};

/// The rest of the nodelet as the status reports it, read by the caller
/// under the locks that guard each part.
struct NodeletSnapshot {
  bool started = false;       ///< the nodelet started (else an ERROR)
  std::string startup_error;  ///< why it did not (empty: see the log)
  std::size_t database_size = 0, indexed = 0, thumbnail_bytes = 0;
  bool has_intrinsics = false, has_odometry = false, has_positions = false;
  std::size_t dropped = 0;  ///< frames the queue dropped so far
};

class NodeletDiagnostics {
 public:
  using Clock = std::chrono::steady_clock;

  /// `now` is the clock the windows are measured on (tests pass their own).
  explicit NodeletDiagnostics(std::function<Clock::time_point()> now = &Clock::now);

  /// Once the nodelet read its parameters and resolved its topics (the
  /// defaults hold until then).
  void configure(const DiagnosticsSettings& settings);

  // Events.
  /// A frame arrived and the keyframe gate decided on it (stamp-order skips
  /// and new runs after a time jump are counted from the decision).
  void frameReceived(double stamp, GateDecision decision);
  /// An image was refused for `problem` (a rejected frame). True when the
  /// caller should log it: each reason at most every 5 s, so that a burst of
  /// one does not hide another.
  bool badImage(bowg::ImageProblem problem);
  void cameraInfoReceived();
  /// A frame went on without the stamped odometry at its stamp (it waited
  /// ~odometry_wait s, odometry_merge.h): its position and metres driven
  /// are the latest that had come.
  void odometryLate();
  /// A keyframe went through the detector; returns the loops found so far.
  std::size_t keyframeProcessed(const bowg::LoopResult& result, bool outside_odometry,
                                double convert_ms, double feature_ms);
  /// Processing a keyframe failed.
  void keyframeError();
  /// The input subscription failed: an ERROR for as long as the nodelet lives.
  void inputProblem(const std::string& why);

  /// Fills `status`: the values, then the worst level with every reason at
  /// that level. Starts a new window for the rates and mean timings.
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status,
                const NodeletSnapshot& nodelet);

 private:
  // Sums since the last diagnose() (for means per window).
  struct Window {
    std::size_t keyframes = 0;
    double convert_ms = 0, feature_ms = 0, transform_ms = 0, word_groups_ms = 0, query_ms = 0,
           islands_ms = 0, verification_ms = 0, total_ms = 0;
    Clock::time_point start;
  };

  void addValues(diagnostic_updater::DiagnosticStatusWrapper& status,
                 const NodeletSnapshot& nodelet) const;
  /// The warnings about the input, each while its cause happened within the
  /// window (the totals stay in the values).
  void inputWarnings(const NodeletSnapshot& nodelet, std::vector<std::string>* warnings);
  /// "no image on <topic> for N s", and what a camera_info arriving alone means.
  std::string silenceWarning(double seconds, bool camera_info) const;
  void noteFrame();

  const std::function<Clock::time_point()> now_;
  mutable std::mutex mutex_;  // guards everything below
  DiagnosticsSettings settings_;
  std::size_t frames_received_ = 0, keyframes_ = 0, loops_ = 0;
  std::size_t metric_loops_ = 0;             ///< loops with a metric translation
  std::size_t metric_outside_odometry_ = 0;  ///< metric translations the odometry rules out
  std::size_t skipped_out_of_order_ = 0, errors_ = 0, time_jump_resets_ = 0;
  std::size_t odometry_late_ = 0;  ///< frames that went on without their reading
  /// Images refused, by reason (bowg/features/image_check.h): the same
  /// reasons the offline tools count.
  bowg::ImageProblemCounts bad_images_;
  /// When a refusal of each reason was last logged.
  std::array<Clock::time_point, bowg::kImageProblemCount> bad_image_logged_{};
  std::string last_stamp_rejection_;  ///< the latest stamp-order skip
  std::string input_problem_;         ///< why the input subscription failed (empty: fine)
  // When each condition last happened: a condition is reported while it
  // happened within the window.
  Clock::time_point started_, last_frame_, last_camera_info_, last_rejected_, last_stamp_skip_,
      last_drop_, last_error_, last_odometry_late_;
  bool any_frame_ = false, any_camera_info_ = false;
  std::size_t drops_seen_ = 0;
  Window window_;
};

}  // namespace bowg_ros
