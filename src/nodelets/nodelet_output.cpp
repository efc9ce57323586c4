// LoopDetectorNodelet: what it publishes per keyframe (loop_closure,
// ~keyframe_status, the lazy ~debug_image) and the diagnostics.
#include "loop_detector_nodelet.h"

namespace bowg_ros {

void LoopDetectorNodelet::publishResult(const Frame& frame, const bowg::LoopResult& result,
                                        const cv::Mat& grey, std::size_t num_features,
                                        std::size_t database_size, double convert_ms,
                                        double feature_ms) {
  const bool found = result.status == bowg::LoopStatus::kLoopDetected;
  if (found) {
    NODELET_INFO("loop: keyframe %u matches %u (score %.3f, %d inliers)", result.query_id,
                 result.match_id, result.best.eta, result.inliers);
    loop_pub_.publish(toLoopClosure(result, frame.header, publish_correspondences_));
  }
  status_pub_.publish(toKeyframeStatus(result, frame.header, detector_->options(), num_features,
                                       database_size, convert_ms, feature_ms));

  // Lazy: the debug image is drawn, and images are cached, only while
  // somebody subscribes.
  if (debug_pub_.getNumSubscribers() > 0 && !grey.empty()) {
    cv::Mat match;
    if (found) {
      auto it = debug_cache_.find(result.match_id);
      if (it != debug_cache_.end()) match = it->second;
    }
    const std::string caption = "keyframe " + std::to_string(result.query_id) + ": " +
                                bowg::toString(result.status) +
                                (found ? " -> " + std::to_string(result.match_id) + ", " +
                                             std::to_string(result.inliers) + " inliers"
                                       : std::string());
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

void LoopDetectorNodelet::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::size_t database_size = 0;
  {
    std::lock_guard<std::mutex> lock(detector_mutex_);
    if (detector_) database_size = detector_->database().size();
  }
  bool has_intrinsics;
  {
    std::lock_guard<std::mutex> lock(intrinsics_mutex_);
    has_intrinsics = intrinsics_.valid;
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
  status.add("loops found", s.loops);
  status.add("dropped frames (queue full)", dropped);
  status.add("skipped frames (stamp order)", s.skipped_out_of_order);
  status.add("dropped frames (unsupported encoding)", s.bad_encoding);
  status.add("dropped frames (malformed image)", s.malformed);
  status.add("dropped frames (more than max_image_pixels)", s.too_large);
  status.add("keyframe errors", s.errors);
  status.add("camera intrinsics known", has_intrinsics);
  status.add("ms convert", s.window_convert_ms / n);
  status.add("ms features", s.window_feature_ms / n);
  status.add("ms words", s.window_transform_ms / n);
  status.add("ms word groups", s.window_word_groups_ms / n);
  status.add("ms query", s.window_query_ms / n);
  status.add("ms islands", s.window_islands_ms / n);
  status.add("ms verification", s.window_verification_ms / n);
  status.add("ms total", s.window_total_ms / n);
  if (!initialised_) {
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "not started (see the log)");
  } else if (s.bad_encoding > 0 || s.malformed > 0 || s.too_large > 0 || s.errors > 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                   "frames rejected (unsupported encoding, malformed or too large images, or "
                   "processing errors)");
  } else if (dropped > 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                   "keyframes dropped: the detector is slower than the keyframe rate");
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "running");
  }
  s.window_keyframes = 0;
  s.window_convert_ms = s.window_feature_ms = s.window_transform_ms = s.window_word_groups_ms =
      s.window_query_ms = s.window_islands_ms = s.window_verification_ms = s.window_total_ms = 0;
  s.window_start = Clock::now();
}

}  // namespace bowg_ros
