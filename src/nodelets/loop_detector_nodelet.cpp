// bowg_ros/LoopDetectorNodelet: the thin ROS shell around bowg::LoopDetector.
// Parameters in (through the engine's parameter table), engine call
// on a worker thread, messages out:
//
//   image (+ camera_info) or keyframe_features
//     -> camera callback: encoding check, stamp order, keyframe gate, push
//        (never blocks: bounded queue drops the oldest frame)
//     -> worker thread: grey conversion, features, LoopDetector::process()
//        under the detector lock
//     -> loop_closure, ~keyframe_status, ~debug_image (lazy), diagnostics
//
// dynamic_reconfigure, the services and the worker share the detector through
// one mutex, so an option swap or a database load happens between keyframes.
#include <cv_bridge/cv_bridge.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/camera_common.h>
#include <image_transport/image_transport.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>

#include <algorithm>
#include <atomic>
#include <boost/thread/recursive_mutex.hpp>
#include <chrono>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "bowg/core/errors.h"
#include "bowg/database/database.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/features/feature_extractor.h"
#include "bowg/parameters/parameter_table.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"
#include "bowg_ros/BoWGConfig.h"
#include "bowg_ros/KeyframeFeatures.h"
#include "bowg_ros/KeyframeStatus.h"
#include "bowg_ros/LoadDatabase.h"
#include "bowg_ros/LoopClosure.h"
#include "bowg_ros/SaveDatabase.h"
#include "bowg_ros/bounded_queue.h"
#include "bowg_ros/debug_image.h"
#include "bowg_ros/image_conversion.h"
#include "bowg_ros/keyframe_gate.h"
#include "bowg_ros/live_parameters.h"
#include "bowg_ros/ros_conversions.h"

namespace bowg_ros {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// The nodelet's own private parameters (not engine options); every other
/// private parameter must be a row of the engine's parameter table.
const char* const kNodeParameters[] = {
    "vocabulary_path",    "queue_size",         "min_keyframe_interval",   "min_keyframe_distance",
    "use_compressed",     "use_features_input", "publish_correspondences", "database_load_path",
    "database_save_path", "debug_image_cache",  "image_transport",         "diagnostic_period",
};

bool isNodeParameter(const std::string& name) {
  for (const char* p : kNodeParameters) {
    if (name == p) return true;
  }
  return false;
}

/// Where a loaded database's odometers end (0 when it has none): the gate's
/// odometer continues from there, so the keyframes' odometers keep growing.
double lastOdometer(const bowg::LoopDetector& detector) {
  return std::max(0.0, detector.database().lastOdometer());
}

/// One frame waiting for the worker: exactly one of the three inputs is set.
struct Frame {
  std_msgs::Header header;
  sensor_msgs::ImageConstPtr image;                 // raw image, shared (no copy)
  sensor_msgs::CompressedImageConstPtr compressed;  // decoded by the worker
  KeyframeFeatures::ConstPtr features;              // upstream features
  /// Metres driven when the frame passed the gate (NaN without odometry).
  double odometer = std::numeric_limits<double>::quiet_NaN();
};

/// Counters for the diagnostics, guarded by LoopDetectorNodelet::stats_mutex_.
struct Stats {
  std::size_t frames_received = 0;
  std::size_t keyframes = 0;
  std::size_t loops = 0;
  std::size_t skipped_out_of_order = 0;
  std::size_t bad_encoding = 0;
  std::size_t malformed = 0;  ///< image messages whose layout cannot be read
  std::size_t errors = 0;
  // Sums since the last diagnostics update (for means per window).
  std::size_t window_keyframes = 0;
  double window_convert_ms = 0, window_feature_ms = 0, window_transform_ms = 0,
         window_word_groups_ms = 0, window_query_ms = 0, window_islands_ms = 0,
         window_verification_ms = 0, window_total_ms = 0;
  Clock::time_point window_start = Clock::now();
};

}  // namespace

class LoopDetectorNodelet : public nodelet::Nodelet {
 public:
  ~LoopDetectorNodelet() override;

 private:
  void onInit() override;
  bool loadParameters(ros::NodeHandle& pnh);

  void imageCallback(const sensor_msgs::ImageConstPtr& msg);
  void compressedCallback(const sensor_msgs::CompressedImageConstPtr& msg);
  void featuresCallback(const KeyframeFeatures::ConstPtr& msg);
  void cameraInfoCallback(const sensor_msgs::CameraInfoConstPtr& msg);
  void odometryCallback(const nav_msgs::OdometryConstPtr& msg);
  /// Stamp order + keyframe gate; true when `frame` was queued.
  bool offer(Frame frame);

  void workerLoop();
  void processFrame(const Frame& frame);

  void reconfigure(BoWGConfig& config, uint32_t level);
  bool saveDatabase(SaveDatabase::Request& req, SaveDatabase::Response& res);
  bool loadDatabase(LoadDatabase::Request& req, LoadDatabase::Response& res);
  bool resetDatabase(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  // Parameters.
  std::string vocabulary_path_, database_load_path_, database_save_path_;
  int queue_size_ = 2;
  int debug_image_cache_ = 200;
  bool use_compressed_ = false, use_features_input_ = false, publish_correspondences_ = false;
  KeyframeGateOptions gate_options_;

  // Engine, guarded by detector_mutex_ (worker, dynamic_reconfigure, services).
  std::mutex detector_mutex_;
  bowg::PipelineOptions options_;
  std::shared_ptr<const bowg::Vocabulary> vocabulary_;
  std::unique_ptr<bowg::FeatureExtractor> extractor_;
  std::unique_ptr<bowg::LoopDetector> detector_;
  std::map<bowg::EntryId, cv::Mat> debug_cache_;  // keyframe images while debugging

  // Camera callback side.
  std::mutex gate_mutex_;
  KeyframeGate gate_;
  std::mutex intrinsics_mutex_;
  bowg::CameraIntrinsics intrinsics_;
  std::atomic<bool> intrinsics_warned_{false};

  std::unique_ptr<BoundedQueue<Frame>> queue_;
  std::thread worker_;
  bool initialised_ = false;

  std::mutex stats_mutex_;
  Stats stats_;

  // ROS interfaces.
  std::unique_ptr<image_transport::ImageTransport> it_, private_it_;
  image_transport::Subscriber image_sub_;
  ros::Subscriber compressed_sub_, features_sub_, info_sub_, odom_sub_;
  ros::Publisher loop_pub_, status_pub_;
  image_transport::Publisher debug_pub_;
  ros::ServiceServer save_srv_, load_srv_, reset_srv_;
  boost::recursive_mutex config_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<BoWGConfig>> reconfigure_server_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diagnostics_timer_;
};

LoopDetectorNodelet::~LoopDetectorNodelet() {
  // Stop the inputs and the timer first, then the worker, then save.
  image_sub_.shutdown();
  compressed_sub_.shutdown();
  features_sub_.shutdown();
  odom_sub_.shutdown();
  diagnostics_timer_.stop();
  if (queue_) queue_->shutdown();
  if (worker_.joinable()) worker_.join();
  if (initialised_ && !database_save_path_.empty()) {
    std::lock_guard<std::mutex> lock(detector_mutex_);
    try {
      detector_->save(database_save_path_);
      NODELET_INFO("saved %zu keyframes to %s", detector_->database().size(),
                   database_save_path_.c_str());
    } catch (const std::exception& e) {
      NODELET_ERROR("could not save the database at shutdown: %s", e.what());
    }
  }
}

bool LoopDetectorNodelet::loadParameters(ros::NodeHandle& pnh) {
  pnh.param<std::string>("vocabulary_path", vocabulary_path_, "");
  pnh.param("queue_size", queue_size_, 2);
  pnh.param("min_keyframe_interval", gate_options_.min_interval, 0.0);
  pnh.param("min_keyframe_distance", gate_options_.min_distance, 0.0);
  pnh.param("use_compressed", use_compressed_, false);
  pnh.param("use_features_input", use_features_input_, false);
  pnh.param("publish_correspondences", publish_correspondences_, false);
  pnh.param<std::string>("database_load_path", database_load_path_, "");
  pnh.param<std::string>("database_save_path", database_save_path_, "");
  pnh.param("debug_image_cache", debug_image_cache_, 200);
  if (queue_size_ < 1) {
    NODELET_FATAL("~queue_size must be >= 1 (got %d)", queue_size_);
    return false;
  }
  try {
    gate_options_.validate();
  } catch (const std::exception& e) {
    NODELET_FATAL("%s", e.what());
    return false;
  }

  // Engine options: every other private parameter must be a table row, so a
  // misspelled key is an error instead of a silently ignored setting.
  std::vector<std::string> names;
  ros::param::getParamNames(names);
  const std::string prefix = pnh.getNamespace() + "/";
  std::map<std::string, std::string> values;
  for (const std::string& full : names) {
    if (full.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string name = full.substr(prefix.size());
    if (name.find('/') != std::string::npos || isNodeParameter(name)) continue;
    XmlRpc::XmlRpcValue v;
    if (!pnh.getParam(name, v)) continue;
    switch (v.getType()) {
      case XmlRpc::XmlRpcValue::TypeBoolean:
        values[name] = bool(v) ? "true" : "false";
        break;
      case XmlRpc::XmlRpcValue::TypeInt:
        values[name] = std::to_string(int(v));
        break;
      case XmlRpc::XmlRpcValue::TypeDouble: {
        std::ostringstream s;
        s.precision(17);
        s << double(v);
        values[name] = s.str();
        break;
      }
      case XmlRpc::XmlRpcValue::TypeString:
        values[name] = std::string(v);
        break;
      default:
        NODELET_FATAL("parameter %s: only scalars are allowed", full.c_str());
        return false;
    }
  }
  try {
    bowg::applyParameters(values, &options_, pnh.getNamespace());
  } catch (const std::exception& e) {
    NODELET_FATAL("invalid parameters: %s", e.what());
    return false;
  }
  return true;
}

void LoopDetectorNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  if (!loadParameters(pnh)) {
    NODELET_FATAL("bowg_ros: not started (fix the parameters above)");
    return;
  }
  if (vocabulary_path_.empty()) {
    NODELET_FATAL(
        "~vocabulary_path is not set: the loop detector needs a vocabulary "
        "(.bowgvoc, DBoW2/DBoW3 YAML, DBoW3 binary, ORBvoc.txt or VINS .bin)");
    return;
  }
  try {
    const auto t0 = Clock::now();
    vocabulary_ = std::make_shared<const bowg::Vocabulary>(bowg::loadVocabulary(vocabulary_path_));
    NODELET_INFO("vocabulary %s: k=%d L=%d, %zu words (%.0f ms)", vocabulary_path_.c_str(),
                 vocabulary_->branching(), vocabulary_->depth(), vocabulary_->wordCount(),
                 msSince(t0));
    // The direct index needs an existing level.
    for (const std::string& c : bowg::correctLiveParameters(vocabulary_->depth(), &options_)) {
      NODELET_WARN("%s", c.c_str());
    }
    extractor_.reset(new bowg::FeatureExtractor(options_.features));
    detector_.reset(new bowg::LoopDetector(vocabulary_, options_.detector));
  } catch (const std::exception& e) {
    NODELET_FATAL("bowg_ros: not started: %s", e.what());
    return;
  }
  if (!database_load_path_.empty()) {
    try {
      detector_->load(database_load_path_);
      NODELET_INFO("loaded %zu keyframes from %s", detector_->database().size(),
                   database_load_path_.c_str());
    } catch (const std::exception& e) {
      NODELET_ERROR("could not load ~database_load_path, starting with an empty database: %s",
                    e.what());
    }
  }
  gate_.setOptions(gate_options_);
  gate_.setOdometer(lastOdometer(*detector_));
  queue_.reset(new BoundedQueue<Frame>(static_cast<std::size_t>(queue_size_)));

  // Outputs.
  loop_pub_ = nh.advertise<LoopClosure>("loop_closure", 10);
  status_pub_ = pnh.advertise<KeyframeStatus>("keyframe_status", 50);
  private_it_.reset(new image_transport::ImageTransport(pnh));
  debug_pub_ = private_it_->advertise("debug_image", 1);

  // Services on the multi-threaded handle: a save does not hold up images.
  ros::NodeHandle& mt_pnh = getMTPrivateNodeHandle();
  save_srv_ = mt_pnh.advertiseService("save_database", &LoopDetectorNodelet::saveDatabase, this);
  load_srv_ = mt_pnh.advertiseService("load_database", &LoopDetectorNodelet::loadDatabase, this);
  reset_srv_ = mt_pnh.advertiseService("reset", &LoopDetectorNodelet::resetDatabase, this);

  // Diagnostics: updated from a wall timer (update() rate-limits itself).
  updater_.reset(new diagnostic_updater::Updater(nh, pnh, getName()));
  updater_->setHardwareID("bowg_ros");
  updater_->add("loop detector", this, &LoopDetectorNodelet::diagnose);
  diagnostics_timer_ = nh.createWallTimer(
      ros::WallDuration(0.5), [this](const ros::WallTimerEvent&) { updater_->update(); });

  // Live tuning: the server calls reconfigure() once now with the current
  // parameters (the same names the options were read from).
  reconfigure_server_.reset(new dynamic_reconfigure::Server<BoWGConfig>(config_mutex_, pnh));
  reconfigure_server_->setCallback(
      [this](BoWGConfig& config, uint32_t level) { reconfigure(config, level); });

  worker_ = std::thread(&LoopDetectorNodelet::workerLoop, this);
  initialised_ = true;

  // Inputs last, once everything they feed exists. The callbacks only gate
  // and enqueue; the subscriber queues are at least ~queue_size deep so that a
  // large ~queue_size makes a fast bag replay lossless (drops then happen, and
  // are counted, only in our own queue).
  const int input_queue = std::max(5, queue_size_);
  if (use_features_input_) {
    features_sub_ =
        nh.subscribe("keyframe_features", input_queue, &LoopDetectorNodelet::featuresCallback, this);
  } else if (use_compressed_) {
    // Debian lacks the compressed image_transport plugin: subscribe to the
    // CompressedImage topic directly and decode with cv::imdecode.
    compressed_sub_ = nh.subscribe(nh.resolveName("image") + "/compressed", input_queue,
                                   &LoopDetectorNodelet::compressedCallback, this);
  } else {
    it_.reset(new image_transport::ImageTransport(nh));
    try {
      image_sub_ =
          it_->subscribe("image", input_queue, &LoopDetectorNodelet::imageCallback, this,
                         image_transport::TransportHints("raw", ros::TransportHints(), pnh));
    } catch (const std::exception& e) {
      NODELET_FATAL("cannot subscribe to %s: %s (for compressed input set ~use_compressed)",
                    nh.resolveName("image").c_str(), e.what());
    }
  }
  // Intrinsics (for the relative pose) also in features mode: camera_info is
  // the sibling of the image topic, image_pipeline's convention.
  info_sub_ = nh.subscribe(image_transport::getCameraInfoTopic(nh.resolveName("image")), 1,
                           &LoopDetectorNodelet::cameraInfoCallback, this);
  // Odometry feeds the distance gate and the keyframes' odometer (windows in
  // metres: recent_exclusion_m, alignment_window_m, max_island_distance_m);
  // without a publisher those fall back to keyframes.
  odom_sub_ = nh.subscribe("odom", 50, &LoopDetectorNodelet::odometryCallback, this);
  NODELET_INFO("bowg_ros ready: input %s, keyframe interval %.3f s, distance %.3f m, queue %d",
               use_features_input_ ? nh.resolveName("keyframe_features").c_str()
                                   : nh.resolveName("image").c_str(),
               gate_options_.min_interval, gate_options_.min_distance, queue_size_);
}

bool LoopDetectorNodelet::offer(Frame frame) {
  GateDecision d;
  {
    std::lock_guard<std::mutex> lock(gate_mutex_);
    d = gate_.check(frame.header.stamp.toSec());
    frame.odometer = gate_.odometer();
  }
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.frames_received;
    if (d == GateDecision::kOutOfOrder || d == GateDecision::kRepeatedStamp) {
      ++stats_.skipped_out_of_order;
    }
  }
  if (d == GateDecision::kOutOfOrder || d == GateDecision::kRepeatedStamp) {
    NODELET_WARN_THROTTLE(2.0, "frame at %.6f skipped: %s", frame.header.stamp.toSec(),
                          toString(d));
    return false;
  }
  if (d != GateDecision::kAccept) return false;
  queue_->push(std::move(frame));
  return true;
}

void LoopDetectorNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg) {
  if (!isSupportedEncoding(msg->encoding)) {
    {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      ++stats_.bad_encoding;
    }
    NODELET_ERROR_THROTTLE(5.0,
                           "unsupported image encoding '%s' (supported: mono8, mono16, "
                           "bgr8, rgb8, bgra8, rgba8, 8UC1, 16UC1): frame dropped",
                           msg->encoding.c_str());
    return;
  }
  // The layout is checked here, where the drop is counted; the worker
  // converts the message (greyFromImage), sharing its buffer for mono8.
  const std::string problem =
      imageLayoutProblem(msg->width, msg->height, msg->step, msg->data.size(), msg->encoding);
  if (!problem.empty()) {
    // Counted in the diagnostics whatever the throttled log shows.
    {
      std::lock_guard<std::mutex> lock(stats_mutex_);
      ++stats_.malformed;
    }
    NODELET_ERROR_THROTTLE(5.0, "malformed image at %.6f (encoding '%s'): %s: frame dropped",
                           msg->header.stamp.toSec(), msg->encoding.c_str(), problem.c_str());
    return;
  }
  Frame frame;
  frame.header = msg->header;
  frame.image = msg;
  offer(std::move(frame));
}

void LoopDetectorNodelet::compressedCallback(const sensor_msgs::CompressedImageConstPtr& msg) {
  Frame frame;
  frame.header = msg->header;
  frame.compressed = msg;
  offer(std::move(frame));
}

void LoopDetectorNodelet::featuresCallback(const KeyframeFeatures::ConstPtr& msg) {
  Frame frame;
  frame.header = msg->header;
  frame.features = msg;
  offer(std::move(frame));
}

void LoopDetectorNodelet::cameraInfoCallback(const sensor_msgs::CameraInfoConstPtr& msg) {
  const bowg::CameraIntrinsics k = toIntrinsics(*msg);
  std::lock_guard<std::mutex> lock(intrinsics_mutex_);
  intrinsics_ = k;
}

void LoopDetectorNodelet::odometryCallback(const nav_msgs::OdometryConstPtr& msg) {
  const geometry_msgs::Point& p = msg->pose.pose.position;
  std::lock_guard<std::mutex> lock(gate_mutex_);
  gate_.addPosition(p.x, p.y, p.z);
}

void LoopDetectorNodelet::workerLoop() {
  Frame frame;
  while (queue_->pop(&frame)) {
    try {
      processFrame(frame);
    } catch (const std::exception& e) {
      {
        std::lock_guard<std::mutex> lock(stats_mutex_);
        ++stats_.errors;
      }
      NODELET_ERROR_THROTTLE(2.0, "keyframe at %.6f skipped: %s", frame.header.stamp.toSec(),
                             e.what());
    }
    frame = Frame();  // release the image now, not at the next pop
  }
}

void LoopDetectorNodelet::processFrame(const Frame& frame) {
  // 1. Grey image (shared for mono8) or upstream features.
  auto t0 = Clock::now();
  cv::Mat grey;
  if (frame.image) {
    grey = greyFromImage(*frame.image);
  } else if (frame.compressed) {
    grey = greyFromCompressed(*frame.compressed);
  }
  const double convert_ms = msSince(t0);

  bowg::KeyframeInput input;
  input.stamp = frame.header.stamp.toSec();
  input.odometer = frame.odometer;
  {
    std::lock_guard<std::mutex> lock(intrinsics_mutex_);
    input.intrinsics = intrinsics_;
  }
  if (!input.intrinsics.valid && !intrinsics_warned_.exchange(true)) {
    NODELET_WARN(
        "no valid camera_info yet: loop closures carry no relative pose "
        "(has_relative_pose = false) until one arrives");
  }

  std::lock_guard<std::mutex> lock(detector_mutex_);
  t0 = Clock::now();
  if (frame.features) {
    input.features = fromMessage(*frame.features);
  } else {
    input.features = extractor_->extract(grey);
  }
  const double feature_ms = frame.features ? 0.0 : msSince(t0);
  const std::size_t num_features = input.features.size();

  const bowg::LoopResult result = detector_->process(input);
  const std::size_t database_size = detector_->database().size();
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

  std::lock_guard<std::mutex> stats_lock(stats_mutex_);
  ++stats_.keyframes;
  ++stats_.window_keyframes;
  if (found) ++stats_.loops;
  stats_.window_convert_ms += convert_ms;
  stats_.window_feature_ms += feature_ms;
  stats_.window_transform_ms += result.timings.transform_ms;
  stats_.window_word_groups_ms += result.timings.word_groups_ms;
  stats_.window_query_ms += result.timings.query_ms;
  stats_.window_islands_ms += result.timings.islands_ms;
  stats_.window_verification_ms += result.timings.verification_ms;
  stats_.window_total_ms += result.timings.total_ms + convert_ms + feature_ms;
}

void LoopDetectorNodelet::reconfigure(BoWGConfig& config, uint32_t /*level*/) {
  if (!detector_) return;
  std::lock_guard<std::mutex> lock(detector_mutex_);
  // Every cfg parameter by name through the parameter table (live_parameters.h).
  dynamic_reconfigure::Config values;
  config.__toMessage__(values);
  bowg::PipelineOptions next = options_;
  try {
    applyLiveConfig(values, &next);
    for (const std::string& c : bowg::correctLiveParameters(vocabulary_->depth(), &next)) {
      NODELET_WARN("dynamic_reconfigure: %s", c.c_str());
    }
    detector_->setOptions(next.detector);  // validates; applies from the next keyframe
    options_ = next;
  } catch (const std::exception& e) {
    NODELET_WARN("dynamic_reconfigure: rejected (%s); keeping the previous values", e.what());
  }
  // Send the values in force back to the client (corrected or kept).
  writeLiveConfig(options_, &values);
  config.__fromMessage__(values);
}

bool LoopDetectorNodelet::saveDatabase(SaveDatabase::Request& req, SaveDatabase::Response& res) {
  const std::string path = req.path.empty() ? database_save_path_ : req.path;
  if (path.empty()) {
    res.success = false;
    res.message = "no path given and ~database_save_path is not set";
    return true;
  }
  std::lock_guard<std::mutex> lock(detector_mutex_);
  try {
    detector_->save(path);
    res.success = true;
    res.message = "saved " + std::to_string(detector_->database().size()) + " keyframes to " + path;
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
  std::lock_guard<std::mutex> lock(detector_mutex_);
  try {
    detector_->load(path);  // keeps the running database on any error
    debug_cache_.clear();
    {
      // Stamps restart from the loaded database's; let the gate follow.
      std::lock_guard<std::mutex> gate_lock(gate_mutex_);
      gate_.reset();
      gate_.setOdometer(lastOdometer(*detector_));
    }
    res.success = true;
    res.message =
        "loaded " + std::to_string(detector_->database().size()) + " keyframes from " + path;
    NODELET_INFO("%s", res.message.c_str());
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string(e.what()) + " (the running database is kept)";
    NODELET_ERROR("load_database: %s", res.message.c_str());
  }
  return true;
}

bool LoopDetectorNodelet::resetDatabase(std_srvs::Trigger::Request&,
                                        std_srvs::Trigger::Response& res) {
  queue_->clear();
  std::lock_guard<std::mutex> lock(detector_mutex_);
  const std::size_t n = detector_->database().size();
  detector_->reset();
  debug_cache_.clear();
  {
    std::lock_guard<std::mutex> gate_lock(gate_mutex_);
    gate_.reset();
  }
  res.success = true;
  res.message = "forgot " + std::to_string(n) + " keyframes";
  NODELET_INFO("reset: %s", res.message.c_str());
  return true;
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
  } else if (s.bad_encoding > 0 || s.malformed > 0 || s.errors > 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                   "frames rejected (unsupported encoding, malformed images or processing "
                   "errors)");
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

PLUGINLIB_EXPORT_CLASS(bowg_ros::LoopDetectorNodelet, nodelet::Nodelet)
