// NodeletDiagnostics: the counters behind the nodelet's "loop detector"
// status, and the status itself.
#include "bowg_ros/nodelet_diagnostics.h"

#include <cstdio>
#include <utility>

namespace bowg_ros {

NodeletDiagnostics::NodeletDiagnostics(std::function<Clock::time_point()> now)
    : now_(std::move(now)) {
  started_ = now_();
  window_.start = started_;
}

void NodeletDiagnostics::configure(const DiagnosticsSettings& settings) {
  std::lock_guard<std::mutex> lock(mutex_);
  settings_ = settings;
}

void NodeletDiagnostics::noteFrame() {
  last_frame_ = now_();
  any_frame_ = true;
}

void NodeletDiagnostics::frameReceived(double stamp, GateDecision decision) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++frames_received_;
  noteFrame();
  if (isStampRejection(decision)) {
    ++skipped_out_of_order_;
    last_stamp_skip_ = last_frame_;
    char text[160];
    std::snprintf(text, sizeof text, "frame at %.6f s: %s", stamp, toString(decision));
    last_stamp_rejection_ = text;
  }
  if (decision == GateDecision::kTimeJump) ++time_jump_resets_;
}

void NodeletDiagnostics::odometryLate() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++odometry_late_;
  last_odometry_late_ = now_();
}

bool NodeletDiagnostics::badImage(bowg::ImageProblem problem) {
  std::lock_guard<std::mutex> lock(mutex_);
  bad_images_.add(problem);
  noteFrame();
  last_rejected_ = last_frame_;
  Clock::time_point& logged = bad_image_logged_[static_cast<std::size_t>(problem)];
  const bool log = last_frame_ - logged >= std::chrono::seconds(5);
  if (log) logged = last_frame_;
  return log;
}

void NodeletDiagnostics::cameraInfoReceived() {
  std::lock_guard<std::mutex> lock(mutex_);
  last_camera_info_ = now_();
  any_camera_info_ = true;
}

std::size_t NodeletDiagnostics::keyframeProcessed(const bowg::LoopResult& result,
                                                  bool outside_odometry, double convert_ms,
                                                  double feature_ms) {
  const bool found = result.status == bowg::LoopStatus::kLoopDetected;
  std::lock_guard<std::mutex> lock(mutex_);
  ++keyframes_;
  ++window_.keyframes;
  if (found) ++loops_;
  if (found && result.translation_scale_known) ++metric_loops_;
  if (outside_odometry) ++metric_outside_odometry_;
  window_.convert_ms += convert_ms;
  window_.feature_ms += feature_ms;
  window_.transform_ms += result.timings.transform_ms;
  window_.word_groups_ms += result.timings.word_groups_ms;
  window_.query_ms += result.timings.query_ms;
  window_.islands_ms += result.timings.islands_ms;
  window_.verification_ms += result.timings.verification_ms;
  window_.total_ms += result.timings.total_ms + convert_ms + feature_ms;
  return loops_;
}

void NodeletDiagnostics::keyframeError() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++errors_;
  last_error_ = now_();
}

void NodeletDiagnostics::inputProblem(const std::string& why) {
  std::lock_guard<std::mutex> lock(mutex_);
  input_problem_ = why;
}

void NodeletDiagnostics::addValues(diagnostic_updater::DiagnosticStatusWrapper& status,
                                   const NodeletSnapshot& nodelet) const {
  const double seconds = std::chrono::duration<double>(now_() - window_.start).count();
  const double n = window_.keyframes > 0 ? double(window_.keyframes) : 1.0;
  status.add("keyframe rate (Hz)", seconds > 0 ? window_.keyframes / seconds : 0.0);
  status.add("frames received", frames_received_);
  status.add("keyframes", keyframes_);
  status.add("database size", nodelet.database_size);
  // Fewer than the database size with indexed_per_place: what a query walks.
  status.add("keyframes in the inverse index", nodelet.indexed);
  status.add("debug thumbnails (kB)", nodelet.thumbnail_bytes / 1024.0);
  status.add("loops found", loops_);
  status.add("loops with a metric translation", metric_loops_);
  status.add("metric translations outside the odometry (published without scale)",
             metric_outside_odometry_);
  status.add("dropped frames (queue full)", nodelet.dropped);
  status.add("skipped frames (stamp order)", skipped_out_of_order_);
  if (!last_stamp_rejection_.empty()) status.add("last stamp-order skip", last_stamp_rejection_);
  status.add("new runs (time jumped back)", time_jump_resets_);
  status.add("frames without the odometry at their stamp", odometry_late_);
  // One value per reason of bowg::ImageProblem, named as the tools name them.
  for (std::size_t i = 1; i < bowg::kImageProblemCount; ++i) {
    const auto reason = static_cast<bowg::ImageProblem>(i);
    status.add(std::string("dropped images (") + bowg::imageProblemName(reason) + ")",
               bad_images_.count(reason));
  }
  status.add("keyframe errors", errors_);
  status.add("camera intrinsics known", nodelet.has_intrinsics);
  status.add("odometry received", nodelet.has_odometry);
  status.add("odometry input", !nodelet.has_odometry   ? "none (images only)"
                               : nodelet.has_positions ? "positions and odometer"
                                                       : "odometer only");
  status.add("ms convert", window_.convert_ms / n);
  status.add("ms features", window_.feature_ms / n);
  status.add("ms words", window_.transform_ms / n);
  status.add("ms word groups", window_.word_groups_ms / n);
  status.add("ms query", window_.query_ms / n);
  status.add("ms islands", window_.islands_ms / n);
  status.add("ms verification", window_.verification_ms / n);
  status.add("ms total", window_.total_ms / n);
}

void NodeletDiagnostics::inputWarnings(const NodeletSnapshot& nodelet,
                                       std::vector<std::string>* warnings) {
  const Clock::time_point now = now_();
  const double window_s = settings_.window;
  const auto seconds = [now](Clock::time_point t) {
    return std::chrono::duration<double>(now - t).count();
  };
  const auto recent = [&](bool happened, Clock::time_point t) {
    return happened && seconds(t) <= window_s;
  };
  // The queue counts its drops; a drop "happened" when that count grew.
  if (nodelet.dropped > drops_seen_) {
    drops_seen_ = nodelet.dropped;
    last_drop_ = now;
  }
  char window[48];
  std::snprintf(window, sizeof window, " in the last %.0f s", window_s);
  const bool rejected = bad_images_.total() > 0;
  if (recent(rejected, last_rejected_) || recent(errors_ > 0, last_error_)) {
    warnings->push_back(std::string("frames rejected") + window +
                        " (bad images: see \"dropped images (...)\", or processing errors)");
  }
  if (recent(skipped_out_of_order_ > 0, last_stamp_skip_)) {
    warnings->push_back(std::to_string(skipped_out_of_order_) +
                        " frames skipped for their stamps (latest: " + last_stamp_rejection_ +
                        "); a replay that starts over needs ~reset or ~reset_on_time_jump");
  }
  if (recent(odometry_late_ > 0, last_odometry_late_)) {
    warnings->push_back(
        std::to_string(odometry_late_) + " frames went on without the odometry " +
        "at their stamp on " + settings_.odom_topic + " or " + settings_.odometer_stamped_topic +
        " (waited ~odometry_wait): the readings come late, stopped, or are stamped on "
        "another clock than the images");
  }
  if (settings_.distance_gate && !nodelet.has_odometry && frames_received_ > 0) {
    warnings->push_back("~min_keyframe_distance is set but no odometry arrived on " +
                        settings_.odom_topic + ", " + settings_.odometer_topic + " or " +
                        settings_.odometer_stamped_topic + ": only the time gate applies");
  }
  if (recent(nodelet.dropped > 0, last_drop_)) {
    warnings->push_back(std::string("keyframes dropped") + window +
                        ": the detector is slower than the keyframe rate");
  }
  const double silent = seconds(any_frame_ ? last_frame_ : started_);
  if (nodelet.started && input_problem_.empty() && silent > window_s) {
    warnings->push_back(silenceWarning(silent, recent(any_camera_info_, last_camera_info_)));
  }
}

std::string NodeletDiagnostics::silenceWarning(double seconds, bool camera_info) const {
  using Input = DiagnosticsSettings::Input;
  const Input input = settings_.input;
  const std::string topic = input == Input::kFeatures     ? settings_.features_topic
                            : input == Input::kCompressed ? settings_.image_topic + "/compressed"
                                                          : settings_.image_topic;
  char text[512];
  std::snprintf(text, sizeof text, "no %s on %s for %.0f s",
                input == Input::kFeatures ? "keyframe features" : "image", topic.c_str(), seconds);
  std::string warning = text;
  if (camera_info && input != Input::kFeatures) {
    warning += "; camera_info arrives on " + settings_.camera_info_topic +
               (input == Input::kCompressed ? ": is the image topic right?"
                                            : ": a compressed stream? set ~use_compressed");
  }
  return warning;
}

void NodeletDiagnostics::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status,
                                  const NodeletSnapshot& nodelet) {
  std::lock_guard<std::mutex> lock(mutex_);
  addValues(status, nodelet);
  // The worst level wins; every reason at that level is in the message.
  std::vector<std::string> errors, warnings;
  if (!nodelet.started) {
    errors.push_back(nodelet.startup_error.empty() ? "not started (see the log)"
                                                   : "not started: " + nodelet.startup_error);
  }
  if (!input_problem_.empty()) errors.push_back("no input: " + input_problem_);
  inputWarnings(nodelet, &warnings);
  auto join = [](const std::vector<std::string>& v) {
    std::string out;
    for (const std::string& r : v) out += (out.empty() ? "" : "; ") + r;
    return out;
  };
  if (!errors.empty()) {
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, join(errors));
  } else if (!warnings.empty()) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, join(warnings));
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "running");
  }
  window_ = Window();
  window_.start = now_();
}

}  // namespace bowg_ros
