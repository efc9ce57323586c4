// bowg_ros/LoopDetectorNodelet: the thin ROS shell around bowg::LoopDetector.
// Parameters in (through the engine's parameter table), engine call
// on a worker thread, messages out:
//
//   image (+ camera_info) or keyframe_features
//     -> camera callback: encoding check, (with stamped odometry: the
//        wait for the readings at the frame's stamp), stamp order, keyframe
//        gate, push (never blocks: bounded queue drops the oldest frame)
//     -> worker thread: grey conversion, features, LoopDetector::process()
//        under the detector lock
//     -> loop_closure, ~keyframe_status, ~debug_image (lazy), diagnostics
//
// Locks, and what each guards (when two are held, in this order: the
// detector's before the gate's; the helpers' own locks are taken last and
// take no other):
//   detector_mutex_  detector_, extractor_, options_, debug_images_ (its
//                    keyframe ids are the database's), worker_epoch_.
//                    Taken by the worker (one keyframe), live tuning, the
//                    services, diagnose() and the final save, so an option
//                    swap or a database load happens between keyframes.
//                    While frames come, nothing that reads or waits for a
//                    file holds it (a load reads and checks the file first,
//                    then swaps it in; a save serializes under it and writes
//                    after); the final save runs once the worker stopped.
//   gate_mutex_      gate_ (stamp order, odometry), odometry_merge_ and
//                    intrinsics_. Taken by the input callbacks, the
//                    odometer timer, the worker (intrinsics), restartRun()
//                    and diagnose(); frames go into queue_ under it, so
//                    they enter in the order the gate saw them.
//   inside NodeletDiagnostics (diagnostics_): its counters.
//   inside BoundedQueue (queue_): the frames between callbacks and worker.
//
// One class, its member functions grouped by job: loop_detector_nodelet.cpp
// (start-up and shutdown), nodelet_parameters.cpp (private parameters),
// nodelet_input.cpp (callbacks, stamp order, keyframe gate),
// nodelet_worker.cpp (grey image, features, detector), nodelet_output.cpp
// (messages, diagnostics snapshot), nodelet_services.cpp (live tuning,
// database services, restartRun). Two helpers of the ROS layer hold their
// own state: bowg_ros/debug_image_publisher.h (the lazy ~debug_image and its
// keyframe images) and bowg_ros/nodelet_diagnostics.h (the counters and the
// diagnostics status). Private to the nodelet library.
#pragma once

#include <cv_bridge/cv_bridge.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <image_transport/camera_common.h>
#include <image_transport/image_transport.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Float64.h>
#include <std_srvs/Trigger.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/features/feature_extractor.h"
#include "bowg/parameters/parameter_table.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg_ros/KeyframeFeatures.h"
#include "bowg_ros/KeyframeStatus.h"
#include "bowg_ros/LoadDatabase.h"
#include "bowg_ros/LoadReferenceMaps.h"
#include "bowg_ros/LoopClosure.h"
#include "bowg_ros/MergeDatabases.h"
#include "bowg_ros/OdometerStamped.h"
#include "bowg_ros/SaveDatabase.h"
#include "bowg_ros/bounded_queue.h"
#include "bowg_ros/debug_image_publisher.h"
#include "bowg_ros/image_conversion.h"
#include "bowg_ros/keyframe_gate.h"
#include "bowg_ros/live_parameters.h"
#include "bowg_ros/live_tuning_server.h"
#include "bowg_ros/nodelet_diagnostics.h"
#include "bowg_ros/odometry_merge.h"
#include "bowg_ros/ros_conversions.h"

namespace bowg_ros {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Where a loaded database's odometers end (0 when it has none): the gate's
/// odometer continues from there, so the keyframes' odometers keep growing.
inline double lastOdometer(const bowg::LoopDetector& detector) {
  return std::max(0.0, detector.database().lastOdometer());
}

/// The stamp of a loaded database's last keyframe, or NaN when it is empty:
/// the gate's stamp floor (the detector refuses older keyframes).
inline double lastStamp(const bowg::LoopDetector& detector) {
  const auto& entries = detector.database().entries();
  return entries.empty() ? std::numeric_limits<double>::quiet_NaN() : entries.back().stamp;
}

/// One frame waiting for the worker: exactly one of the three inputs is set.
struct Frame {
  std_msgs::Header header;
  sensor_msgs::ImageConstPtr image;                 // raw image, shared (no copy)
  sensor_msgs::CompressedImageConstPtr compressed;  // decoded by the worker
  KeyframeFeatures::ConstPtr features;              // upstream features
  /// Metres driven when the frame passed the gate (NaN without odometry).
  double odometer = std::numeric_limits<double>::quiet_NaN();
  /// The odometry position then (the odometry gate; unknown without odometry).
  bowg::OdometryPosition position;
  /// The odometry's heading then (the heading gate; unknown without one).
  bowg::OdometryHeading heading;
  /// The gate's run (KeyframeGate::epoch()): a frame of a newer run than the
  /// worker's starts a new database (time jumped back, ~reset_on_time_jump).
  unsigned epoch = 0;
};

class LoopDetectorNodelet : public nodelet::Nodelet {
 public:
  ~LoopDetectorNodelet() override;

 private:
  /// How a run of the database starts (restartRun()).
  enum class RunStart {
    kEmpty,          ///< ~reset: the database is forgotten, the gate starts over
    kLoaded,         ///< ~load_database adopted a file: the gate continues after it
    kAfterTimeJump,  ///< the gate began a new run itself: the database is forgotten
  };

  void onInit() override;
  /// Vocabulary, feature extractor, detector and the database to resume
  /// from; false (logged FATAL) when the nodelet cannot start.
  bool startEngine();
  /// Logs why the nodelet does not start (FATAL) and keeps it for the
  /// diagnostics; returns false.
  bool fatal(const std::string& why);
  void startDiagnostics(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  /// The topics the diagnostics' warnings name, and their window.
  DiagnosticsSettings diagnosticsSettings() const;
  void advertiseInterfaces(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  void subscribeInputs(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  void subscribeOdometry(ros::NodeHandle& nh);
  bool loadParameters(ros::NodeHandle& pnh);
  /// Every other private parameter into options_ through the engine's
  /// parameter table; false (fatal()) on an unknown or invalid one.
  bool loadEngineParameters(ros::NodeHandle& pnh);
  /// A public topic name (image, loop_closure, ...) resolved and remapped in
  /// the nodelet's own namespace, whatever the manager's namespace.
  std::string publicName(const std::string& name) const;

  void imageCallback(const sensor_msgs::ImageConstPtr& msg);
  void compressedCallback(const sensor_msgs::CompressedImageConstPtr& msg);
  void featuresCallback(const KeyframeFeatures::ConstPtr& msg);
  void cameraInfoCallback(const sensor_msgs::CameraInfoConstPtr& msg);
  void odometryCallback(const nav_msgs::OdometryConstPtr& msg);
  void odometerCallback(const std_msgs::Float64ConstPtr& msg);
  void odometerStampedCallback(const OdometerStamped::ConstPtr& msg);
  /// One odometry reading (a position or metres driven, from any of the
  /// three topics) into the gate; an ignored odometer reading is logged.
  /// gate_mutex_ held.
  void applyReading(const OdometryReading& r);
  /// A stamped reading from `topic` (odom, odometer_stamped) into the
  /// merge: one older than its topic's previous is dropped with a warning,
  /// or, far back with ~reset_on_time_jump, starts the topic's run over;
  /// then the merge's ready frames go on. gate_mutex_ held.
  void addStampedReading(double stamp, const OdometryReading& r, const char* topic);
  /// True when frames wait for stamped odometry (odometry_merge.h): a
  /// reading on odom or odometer_stamped, a publisher on odometer_stamped,
  /// or frames still waiting. gate_mutex_ held.
  bool waitsForOdometry() const;
  /// Hands on what the stamped odometry's merge holds ready; gate_mutex_ held.
  void releaseMerged();
  void reportOdometryInput(bowg::OdometryInput input);
  /// A frame in: through the stamped odometry's merge when there is one,
  /// else straight to admit().
  void offer(Frame frame);
  /// Stamp order + keyframe gate, then the queue; `odometry_late`: it went
  /// on without its odometer reading. gate_mutex_ held.
  void admit(Frame frame, bool odometry_late);

  void workerLoop();
  void processFrame(const Frame& frame);
  /// The latest camera_info's intrinsics; warns once while none is valid.
  bowg::CameraIntrinsics currentIntrinsics();
  /// The diagnostics and log lines of one processed keyframe.
  void reportKeyframe(const bowg::LoopResult& result, double convert_ms, double feature_ms);
  /// loop_closure, ~keyframe_status and the lazy ~debug_image of one keyframe
  /// (called by the worker under the detector lock).
  void publishResult(const Frame& frame, const bowg::LoopResult& result, const cv::Mat& grey,
                     std::size_t num_features, std::size_t database_size, double convert_ms,
                     double feature_ms);

  /// A new run of the database (see RunStart): forgets the database unless
  /// one was just loaded, forgets the keyframe images (their ids name other
  /// keyframes now) and, unless the gate began the run itself, restarts the
  /// gate where the database ends (its odometer and last stamp). The caller
  /// holds detector_mutex_; takes gate_mutex_ after it.
  void restartRun(RunStart start);

  /// Live tuning: applies `requested` (as the client sent it), reports
  /// start-only and out-of-range values, returns the live values in force.
  dynamic_reconfigure::Config reconfigure(const dynamic_reconfigure::Config& requested);
  bool saveDatabase(SaveDatabase::Request& req, SaveDatabase::Response& res);
  bool loadDatabase(LoadDatabase::Request& req, LoadDatabase::Response& res);
  /// Files only (the vocabulary is read-only after start): no detector lock.
  bool mergeDatabases(MergeDatabases::Request& req, MergeDatabases::Response& res);
  bool loadReferenceMaps(LoadReferenceMaps::Request& req, LoadReferenceMaps::Response& res);
  bool resetDatabase(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  /// The diagnostics timer: the rest of the nodelet's state, read under its
  /// locks one at a time, handed to diagnostics_.
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  /// The database at start: the reference maps and ~database_load_path
  /// merged (a reference map that cannot be read: fatal), or the load path
  /// alone (an error: logged, empty database). False when not started.
  bool loadStartDatabase();
  /// Puts the keyframes that follow in the configured mission
  /// (~mission_name, ~mission_id); returns the line that says which. Throws
  /// std::invalid_argument when the database holds the id or the name as
  /// another mission's. Called with detector_mutex_ held or before the
  /// threads start.
  std::string startMission();
  /// Counts (by reason) and logs a refused image: the frame is dropped.
  void dropBadImage(const bowg::ImageCheck& check, const ros::Time& stamp);

  // Parameters (written by onInit() only, before any thread starts).
  std::string vocabulary_path_, database_load_path_, database_save_path_;
  /// The mission the keyframes belong to (LoopDetector::startMission).
  std::string mission_name_;
  int mission_id_ = -1;
  /// Earlier missions' database files loaded at start beside the live
  /// mission (with ~database_load_path, merged: LoopDetector::readMerged).
  std::vector<std::string> reference_maps_;
  int queue_size_ = 2;
  bool use_compressed_ = false, use_features_input_ = false, publish_correspondences_ = false;
  KeyframeGateOptions gate_options_;
  /// s a frame waits for the stamped odometry at its stamp.
  double odometry_wait_ = 0.2;
  double diagnostics_window_ = 30.0;  ///< s: how long a condition stays in the diagnostics
  std::string startup_error_;         ///< why the nodelet did not start (empty: it did)
  /// The feature options at start-up, for their image size limit (not a
  /// live parameter): read by the callbacks without the detector lock.
  bowg::FeatureOptions size_limit_;

  // Engine (see the locks above).
  std::mutex detector_mutex_;
  bowg::PipelineOptions options_;
  std::shared_ptr<const bowg::Vocabulary> vocabulary_;  // set at start, then read-only
  std::unique_ptr<bowg::FeatureExtractor> extractor_;
  std::unique_ptr<bowg::LoopDetector> detector_;
  DebugImagePublisher debug_images_;
  unsigned worker_epoch_ = 0;  ///< the gate's run the database belongs to

  // Camera callback side (see the locks above).
  std::mutex gate_mutex_;
  KeyframeGate gate_;
  OdometryMerge<Frame> odometry_merge_;
  bowg::CameraIntrinsics intrinsics_;

  // Worker thread only.
  bool intrinsics_warned_ = false;  ///< the "no valid camera_info" warning was logged
  // The odometry input of the last keyframe, logged when it changes (-1
  // before the first keyframe).
  int logged_input_ = -1;

  NodeletDiagnostics diagnostics_;              // locks itself
  std::unique_ptr<BoundedQueue<Frame>> queue_;  // locks itself
  std::thread worker_;
  /// The nodelet started (set by onInit(), read by the diagnostics timer).
  std::atomic<bool> initialised_{false};

  // ROS interfaces.
  std::unique_ptr<image_transport::ImageTransport> it_, private_it_;
  image_transport::Subscriber image_sub_;
  ros::Subscriber compressed_sub_, features_sub_, info_sub_, odom_sub_, odometer_sub_,
      odometer_stamped_sub_;
  /// Releases frames that waited ~odometry_wait for their reading.
  ros::WallTimer odometry_timer_;
  ros::Publisher loop_pub_, status_pub_;
  // The services run on a queue and a thread of the nodelet's own, so a long
  // save does not hold up images, and the nodelet's ROS handles use one
  // manager queue only. The manager destroys its two queues of a nodelet
  // before the nodelet when a callback of one of them is still running at
  // unload (the callback holds the nodelet); handles on the other queue would
  // then be shut down on a destroyed queue. Declared before the servers: the
  // queue outlives them.
  ros::CallbackQueue service_queue_;
  std::unique_ptr<ros::AsyncSpinner> service_spinner_;
  // ~load_database on a queue and a thread of its own: reading a file may
  // take long (and, for a file that never ends, until it is refused), and
  // neither save nor reset waits for it.
  ros::CallbackQueue load_queue_;
  std::unique_ptr<ros::AsyncSpinner> load_spinner_;
  ros::ServiceServer save_srv_, load_srv_, merge_srv_, reference_srv_, reset_srv_;
  std::unique_ptr<LiveTuningServer> reconfigure_server_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diagnostics_timer_;
};

}  // namespace bowg_ros
