// LoopDetectorNodelet: what it publishes per keyframe (loop_closure,
// ~keyframe_status, the lazy ~debug_image) and the diagnostics.
#include <cstdio>
#include <string>
#include <vector>

#include "loop_detector_nodelet.h"

namespace bowg_ros {

void LoopDetectorNodelet::forgetKeyframeImages() {
  debug_cache_.clear();
  thumbnails_.clear();
}

void LoopDetectorNodelet::publishResult(const Frame& frame, const bowg::LoopResult& result,
                                        const cv::Mat& grey, std::size_t num_features,
                                        std::size_t database_size, double convert_ms,
                                        double feature_ms) {
  const bool found = result.status == bowg::LoopStatus::kLoopDetected;
  if (found) {
    NODELET_DEBUG("loop: keyframe %u matches %u (score %.3f, %d inliers)", result.query_id,
                  result.match_id, result.best.eta, result.inliers);
    loop_pub_.publish(toLoopClosure(result, frame.header, publish_correspondences_));
  }
  status_pub_.publish(toKeyframeStatus(result, frame.header, detector_->options(), num_features,
                                       database_size, convert_ms, feature_ms));

  // Every keyframe leaves a thumbnail, so that the debug image can show the
  // matched place of any loop (a revisit comes hundreds of keyframes later).
  thumbnails_.add(result.query_id, grey);

  // Lazy: the debug image is drawn, and full images are cached, only while
  // somebody subscribes.
  if (debug_pub_.getNumSubscribers() > 0 && !grey.empty()) {
    // The loop's match, or else the best candidate the checks turned down.
    const bool has_other = found || result.has_candidate;
    const bowg::EntryId other = found ? result.match_id : result.best.entry;
    cv::Mat match;
    bool from_thumbnail = false;
    if (has_other) {
      auto it = debug_cache_.find(other);
      if (it != debug_cache_.end()) {
        match = it->second;
      } else {
        match = thumbnails_.restore(other);
        from_thumbnail = !match.empty();
      }
    }
    char scores[96] = "";
    if (result.has_candidate) {
      std::snprintf(scores, sizeof scores, " (score %.3f, island %u-%u)", result.best.eta,
                    result.island_first, result.island_last);
    }
    std::string caption =
        "keyframe " + std::to_string(result.query_id) + ": " + bowg::toString(result.status);
    if (found) {
      caption += " -> " + std::to_string(result.match_id) + ", " + std::to_string(result.inliers) +
                 " inliers";
    } else if (result.has_candidate) {
      caption += "; best candidate " + std::to_string(result.best.entry);
    }
    caption += std::string("\n") + (result.has_candidate ? scores + 1 : "no candidate");
    if (from_thumbnail) caption += "; match shown from its thumbnail";
    cv_bridge::CvImage out(
        frame.header, "bgr8",
        drawDebugImage(grey, match,
                       found ? result.inlier_correspondences : std::vector<bowg::Correspondence>(),
                       caption));
    debug_pub_.publish(out.toImageMsg());
    // A mono8 grey image shares the message buffer, which cv_bridge does not
    // keep alive beyond the frame: the cache holds its own copy.
    debug_cache_[result.query_id] = grey.clone();
    while (static_cast<int>(debug_cache_.size()) > debug_image_cache_) {
      debug_cache_.erase(debug_cache_.begin());
    }
  } else if (!debug_cache_.empty()) {
    debug_cache_.clear();
  }
}

// Under stats_mutex_: the warnings about the input, each while its cause
// happened within ~diagnostics_window (the totals stay in the values).
void LoopDetectorNodelet::inputWarnings(std::size_t dropped, bool has_odometry,
                                        std::vector<std::string>* warnings) {
  Stats& s = stats_;
  const Clock::time_point now = Clock::now();
  const auto seconds = [now](Clock::time_point t) {
    return std::chrono::duration<double>(now - t).count();
  };
  const auto recent = [&](bool happened, Clock::time_point t) {
    return happened && seconds(t) <= diagnostics_window_;
  };
  if (dropped > s.drops_seen) {
    s.drops_seen = dropped;
    s.last_drop = now;
  }
  char window[48];
  std::snprintf(window, sizeof window, " in the last %.0f s", diagnostics_window_);
  const bool rejected = s.bad_images.total() > 0;
  if (recent(rejected, s.last_rejected) || recent(s.errors > 0, s.last_error)) {
    warnings->push_back(std::string("frames rejected") + window +
                        " (bad images: see \"dropped images (...)\", or processing errors)");
  }
  if (recent(s.skipped_out_of_order > 0, s.last_stamp_skip)) {
    warnings->push_back(std::to_string(s.skipped_out_of_order) +
                        " frames skipped for their stamps (latest: " + s.last_stamp_rejection +
                        "); a replay that starts over needs ~reset or ~reset_on_time_jump");
  }
  if (gate_options_.min_distance > 0.0 && !has_odometry && s.frames_received > 0) {
    warnings->push_back("~min_keyframe_distance is set but no odometry arrived on " +
                        publicName("odom") + " or " + publicName("odometer") +
                        ": only the time gate applies");
  }
  if (recent(dropped > 0, s.last_drop)) {
    warnings->push_back(std::string("keyframes dropped") + window +
                        ": the detector is slower than the keyframe rate");
  }
  const double silent = seconds(s.any_frame ? s.last_frame : s.started);
  if (initialised_ && s.input_problem.empty() && silent > diagnostics_window_) {
    warnings->push_back(silenceWarning(silent, recent(s.any_camera_info, s.last_camera_info)));
  }
}

// "no image on <topic> for N s", and what a camera_info arriving alone means.
std::string LoopDetectorNodelet::silenceWarning(double seconds, bool camera_info) const {
  const std::string topic = use_features_input_ ? publicName("keyframe_features")
                            : use_compressed_   ? publicName("image") + "/compressed"
                                                : publicName("image");
  char text[512];
  std::snprintf(text, sizeof text, "no %s on %s for %.0f s",
                use_features_input_ ? "keyframe features" : "image", topic.c_str(), seconds);
  std::string warning = text;
  if (camera_info && !use_features_input_) {
    warning += "; camera_info arrives on " +
               image_transport::getCameraInfoTopic(publicName("image")) +
               (use_compressed_ ? ": is the image topic right?"
                                : ": a compressed stream? set ~use_compressed");
  }
  return warning;
}

void LoopDetectorNodelet::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::size_t database_size = 0, indexed = 0, thumbnail_bytes = 0;
  {
    std::lock_guard<std::mutex> lock(detector_mutex_);
    if (detector_) {
      database_size = detector_->database().size();
      indexed = detector_->database().searchableCount();
    }
    thumbnail_bytes = thumbnails_.bytes();
  }
  bool has_intrinsics;
  {
    std::lock_guard<std::mutex> lock(intrinsics_mutex_);
    has_intrinsics = intrinsics_.valid;
  }
  bool has_odometry, has_positions;
  {
    std::lock_guard<std::mutex> lock(gate_mutex_);
    has_odometry = gate_.hasOdometry();
    has_positions = gate_.hasPositions();
  }
  const std::size_t dropped = queue_ ? queue_->dropped() : 0;
  std::lock_guard<std::mutex> lock(stats_mutex_);
  Stats& s = stats_;
  const double seconds = std::chrono::duration<double>(Clock::now() - s.window_start).count();
  const double n = s.window_keyframes > 0 ? double(s.window_keyframes) : 1.0;
  status.add("keyframe rate (Hz)", seconds > 0 ? s.window_keyframes / seconds : 0.0);
  status.add("frames received", s.frames_received);
  status.add("keyframes", s.keyframes);
  status.add("database size", database_size);
  // Fewer than the database size with indexed_per_place: what a query walks.
  status.add("keyframes in the inverse index", indexed);
  status.add("debug thumbnails (kB)", thumbnail_bytes / 1024.0);
  status.add("loops found", s.loops);
  status.add("loops with a metric translation", s.metric_loops);
  status.add("metric translations outside the odometry (published without scale)",
             s.metric_outside_odometry);
  status.add("dropped frames (queue full)", dropped);
  status.add("skipped frames (stamp order)", s.skipped_out_of_order);
  if (!s.last_stamp_rejection.empty()) status.add("last stamp-order skip", s.last_stamp_rejection);
  status.add("new runs (time jumped back)", s.time_jump_resets);
  // One value per reason of bowg::ImageProblem, named as the tools name them.
  for (std::size_t i = 1; i < bowg::kImageProblemCount; ++i) {
    const auto reason = static_cast<bowg::ImageProblem>(i);
    status.add(std::string("dropped images (") + bowg::imageProblemName(reason) + ")",
               s.bad_images.count(reason));
  }
  status.add("keyframe errors", s.errors);
  status.add("camera intrinsics known", has_intrinsics);
  status.add("odometry received", has_odometry);
  status.add("odometry input", !has_odometry   ? "none (images only)"
                               : has_positions ? "positions and odometer"
                                               : "odometer only");
  status.add("ms convert", s.window_convert_ms / n);
  status.add("ms features", s.window_feature_ms / n);
  status.add("ms words", s.window_transform_ms / n);
  status.add("ms word groups", s.window_word_groups_ms / n);
  status.add("ms query", s.window_query_ms / n);
  status.add("ms islands", s.window_islands_ms / n);
  status.add("ms verification", s.window_verification_ms / n);
  status.add("ms total", s.window_total_ms / n);
  // The worst level wins; every reason at that level is in the message.
  std::vector<std::string> errors, warnings;
  if (!initialised_) {
    errors.push_back(startup_error_.empty() ? "not started (see the log)"
                                            : "not started: " + startup_error_);
  }
  if (!s.input_problem.empty()) errors.push_back("no input: " + s.input_problem);
  inputWarnings(dropped, has_odometry, &warnings);
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
  s.window_keyframes = 0;
  s.window_convert_ms = s.window_feature_ms = s.window_transform_ms = s.window_word_groups_ms =
      s.window_query_ms = s.window_islands_ms = s.window_verification_ms = s.window_total_ms = 0;
  s.window_start = Clock::now();
}

}  // namespace bowg_ros
