// LoopDetectorNodelet: what it publishes per keyframe (loop_closure,
// ~keyframe_status, the lazy ~debug_image) and the diagnostics' view of the
// nodelet (its settings, and the state the diagnostics timer reports).
#include "loop_detector_nodelet.h"

namespace bowg_ros {

void LoopDetectorNodelet::publishResult(const Frame& frame, const bowg::LoopResult& result,
                                        const cv::Mat& grey, std::size_t num_features,
                                        std::size_t database_size, double convert_ms,
                                        double feature_ms) {
  if (result.status == bowg::LoopStatus::kLoopDetected) {
    NODELET_DEBUG("loop: keyframe %u matches %u (score %.3f, %d inliers)", result.query_id,
                  result.match_id, result.best.eta, result.inliers);
    loop_pub_.publish(toLoopClosure(result, frame.header, publish_correspondences_));
  }
  status_pub_.publish(toKeyframeStatus(result, frame.header, detector_->options(), num_features,
                                       database_size, convert_ms, feature_ms));
  debug_images_.publish(frame.header, result, grey);
}

DiagnosticsSettings LoopDetectorNodelet::diagnosticsSettings() const {
  DiagnosticsSettings settings;
  settings.input = use_features_input_ ? DiagnosticsSettings::Input::kFeatures
                   : use_compressed_   ? DiagnosticsSettings::Input::kCompressed
                                       : DiagnosticsSettings::Input::kImage;
  settings.image_topic = publicName("image");
  settings.features_topic = publicName("keyframe_features");
  settings.camera_info_topic = image_transport::getCameraInfoTopic(publicName("image"));
  settings.odom_topic = publicName("odom");
  settings.odometer_topic = publicName("odometer");
  settings.odometer_stamped_topic = publicName("odometer_stamped");
  settings.window = diagnostics_window_;
  settings.distance_gate = gate_options_.min_distance > 0.0;
  return settings;
}

void LoopDetectorNodelet::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  NodeletSnapshot nodelet;
  nodelet.started = initialised_;
  nodelet.startup_error = startup_error_;
  {
    std::lock_guard<std::mutex> lock(detector_mutex_);
    if (detector_) {
      nodelet.database_size = detector_->database().size();
      nodelet.indexed = detector_->database().searchableCount();
    }
    nodelet.thumbnail_bytes = debug_images_.thumbnailBytes();
  }
  {
    std::lock_guard<std::mutex> lock(gate_mutex_);
    nodelet.has_intrinsics = intrinsics_.valid;
    nodelet.has_odometry = gate_.hasOdometry();
    nodelet.has_positions = gate_.hasPositions();
  }
  nodelet.dropped = queue_ ? queue_->dropped() : 0;
  diagnostics_.diagnose(status, nodelet);
}

}  // namespace bowg_ros
