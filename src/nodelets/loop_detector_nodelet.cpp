// LoopDetectorNodelet: start-up (vocabulary, detector, outputs, services,
// diagnostics, live tuning, inputs last) and an orderly shutdown.
#include "loop_detector_nodelet.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <opencv2/core/version.hpp>
#include <pluginlib/class_list_macros.hpp>

#include "bowg/core/atomic_file.h"
#include "bowg/core/bounded_file.h"
#include "bowg/detection/geometric_verification.h"
#include "bowg_ros/startup_status.h"

namespace bowg_ros {
namespace {

// The size of the file at `path`, or what it is instead of a regular file,
// without opening it (stat() never waits on a FIFO or a device).
std::string describeFileSize(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return std::string("cannot stat: ") + std::strerror(errno);
  if (S_ISREG(st.st_mode)) return bowg::formatBytes(static_cast<std::uint64_t>(st.st_size));
  if (S_ISDIR(st.st_mode)) return "a directory";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  return "not a regular file";
}

}  // namespace

LoopDetectorNodelet::~LoopDetectorNodelet() {
  // Stop the services (waiting for one that runs), the inputs and the timer
  // first, then the worker, then save.
  if (service_spinner_) service_spinner_->stop();
  if (load_spinner_) load_spinner_->stop();
  save_srv_.shutdown();
  load_srv_.shutdown();
  merge_srv_.shutdown();
  reset_srv_.shutdown();
  image_sub_.shutdown();
  compressed_sub_.shutdown();
  features_sub_.shutdown();
  odom_sub_.shutdown();
  odometer_sub_.shutdown();
  odometer_stamped_sub_.shutdown();
  odometry_timer_.stop();
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

bool LoopDetectorNodelet::startEngine() {
  if (vocabulary_path_.empty()) {
    return fatal(
        "~vocabulary_path is not set: the loop detector needs a vocabulary "
        "(.bowgvoc, DBoW2/DBoW3 YAML, DBoW3 binary, ORBvoc.txt or VINS .bin)");
  }
  try {
    // Before the load, which may take seconds (a 145 MB ORBvoc.txt): a slow
    // start is never silent.
    NODELET_INFO("loading vocabulary %s (%s)", vocabulary_path_.c_str(),
                 describeFileSize(vocabulary_path_).c_str());
    const auto t0 = Clock::now();
    vocabulary_ = std::make_shared<const bowg::Vocabulary>(bowg::loadVocabulary(vocabulary_path_));
    NODELET_INFO("vocabulary %s: k=%d L=%d, %zu words (%.0f ms)", vocabulary_path_.c_str(),
                 vocabulary_->branching(), vocabulary_->depth(), vocabulary_->wordCount(),
                 msSince(t0));
    // The direct index needs an existing level.
    for (const std::string& c : bowg::correctLiveParameters(vocabulary_->depth(), &options_)) {
      NODELET_WARN("%s", c.c_str());
    }
    if (options_.detector.geometric.ransac_bound_confidence > 0.0 &&
        !bowg::ransacSampleBoundAvailable(options_.detector.geometric)) {
      NODELET_WARN(
          "~ransac_bound_confidence %g has no effect: this OpenCV (%s) is older than 3.4.10 / "
          "4.3 and its findFundamentalMat takes no sample limit; RANSAC runs up to 1,000 "
          "samples (same loops, more time)",
          options_.detector.geometric.ransac_bound_confidence, CV_VERSION);
    }
    extractor_.reset(new bowg::FeatureExtractor(options_.features));
    size_limit_ = options_.features;
    detector_.reset(new bowg::LoopDetector(vocabulary_, options_.detector));
  } catch (const std::exception& e) {
    return fatal(e.what());
  }
  // Partial copies that saves to these paths left when they were killed
  // (atomic_file.h): the next save would remove them too, but a robot that
  // only loads would keep them for ever.
  for (const std::string& path : {database_save_path_, database_load_path_}) {
    const std::size_t removed = bowg::removeStaleTemporariesOf(path);
    if (removed > 0) {
      NODELET_INFO("removed %zu partial temporary file(s) of an interrupted save of %s", removed,
                   path.c_str());
    }
  }
  if (!loadStartDatabase()) return false;
  try {
    NODELET_INFO("%s", startMission().c_str());
  } catch (const std::exception& e) {
    return fatal(std::string("~mission_name / ~mission_id: ") + e.what());
  }
  return true;
}

bool LoopDetectorNodelet::loadStartDatabase() {
  if (reference_maps_.empty()) {
    if (database_load_path_.empty()) return true;
    try {
      detector_->load(database_load_path_);
      NODELET_INFO("loaded %zu keyframes from %s", detector_->database().size(),
                   database_load_path_.c_str());
    } catch (const std::exception& e) {
      NODELET_ERROR("could not load ~database_load_path, starting with an empty database: %s",
                    e.what());
    }
    return true;
  }
  // Re-inspection against an archive: recording without it is not what the
  // operator asked for.
  std::vector<std::string> files = reference_maps_;
  if (!database_load_path_.empty()) files.push_back(database_load_path_);
  try {
    detector_->adopt(bowg::LoopDetector::readMerged(files, vocabulary_, detector_->options()));
  } catch (const std::exception& e) {
    return fatal(std::string("~reference_maps: ") + e.what());
  }
  std::string list;
  for (const std::string& f : files) list += (list.empty() ? "" : ", ") + f;
  NODELET_INFO("loaded %zu keyframes of %zu mission(s) from %s", detector_->database().size(),
               detector_->database().missions().size(), list.c_str());
  return true;
}

bool LoopDetectorNodelet::fatal(const std::string& why) {
  NODELET_FATAL("bowg_ros: not started: %s", why.c_str());
  startup_error_ = why;
  return false;
}

std::string LoopDetectorNodelet::publicName(const std::string& name) const {
  // getNodeHandle() lives in the parent namespace of the nodelet's name. For
  // a nodelet at the root ("/bowg") that is "/", which roscpp cleans to "" and
  // then resolves in the *manager's* namespace: loaded into a camera's
  // manager (/camera/camera_nodelet_manager), "image" became /camera/image and
  // the launch file's remap (keyed "/image" by the loader) never matched.
  // Resolve in the nodelet's own namespace instead: the absolute name goes
  // through the remappings the loader passed (the private handle holds them).
  return getPrivateNodeHandle().resolveName(
      ros::names::append(ros::names::parentNamespace(getName()), name));
}

// /diagnostics, published twice a second (also when the start failed).
void LoopDetectorNodelet::startDiagnostics(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  updater_.reset(new diagnostic_updater::Updater(nh, pnh, getName()));
  updater_->setHardwareID("bowg_ros");
  updater_->add("loop detector", this, &LoopDetectorNodelet::diagnose);
  diagnostics_timer_ = nh.createWallTimer(
      ros::WallDuration(0.5), [this](const ros::WallTimerEvent&) { updater_->update(); });
}

// Outputs, services, diagnostics and live tuning.
void LoopDetectorNodelet::advertiseInterfaces(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  // Outputs.
  loop_pub_ = nh.advertise<LoopClosure>(publicName("loop_closure"), 10);
  status_pub_ = pnh.advertise<KeyframeStatus>("keyframe_status", 50);
  private_it_.reset(new image_transport::ImageTransport(pnh));
  debug_images_.advertise(*private_it_);

  // Services on the nodelet's own queue and thread (see service_queue_).
  ros::NodeHandle service_pnh(pnh);
  service_pnh.setCallbackQueue(&service_queue_);
  save_srv_ =
      service_pnh.advertiseService("save_database", &LoopDetectorNodelet::saveDatabase, this);
  reset_srv_ = service_pnh.advertiseService("reset", &LoopDetectorNodelet::resetDatabase, this);
  service_spinner_.reset(new ros::AsyncSpinner(1, &service_queue_));
  service_spinner_->start();
  ros::NodeHandle load_pnh(pnh);
  load_pnh.setCallbackQueue(&load_queue_);
  load_srv_ = load_pnh.advertiseService("load_database", &LoopDetectorNodelet::loadDatabase, this);
  merge_srv_ =
      load_pnh.advertiseService("merge_databases", &LoopDetectorNodelet::mergeDatabases, this);
  reference_srv_ = load_pnh.advertiseService("load_reference_maps",
                                             &LoopDetectorNodelet::loadReferenceMaps, this);
  load_spinner_.reset(new ros::AsyncSpinner(1, &load_queue_));
  load_spinner_->start();

  // Diagnostics: updated from a wall timer (update() rate-limits itself).
  startDiagnostics(nh, pnh);

  // Live tuning: the values in force were read from the same names at start.
  reconfigure_server_.reset(new LiveTuningServer(
      pnh, describeWithStartOnly(options_), liveConfig(options_),
      [this](const dynamic_reconfigure::Config& requested) { return reconfigure(requested); }));
}

// Odometry: positions, an odometer, a stamped odometer. Subscribed before
// the frames (a frame's callback asks whether the stamped odometer has a
// publisher).
void LoopDetectorNodelet::subscribeOdometry(ros::NodeHandle& nh) {
  // Odometry feeds the distance gate and the keyframes' odometer (windows in
  // metres: recent_exclusion_m, alignment_window_m, max_island_distance_m);
  // without a publisher those fall back to keyframes. Stamped positions
  // (the usual) go through the merge as odometer_stamped's readings do: a
  // frame gets the position at its stamp.
  odom_sub_ = nh.subscribe(publicName("odom"), 50, &LoopDetectorNodelet::odometryCallback, this);
  // A robot without positions may still count the metres it drives (a
  // crawler's cable counter): std_msgs/Float64 on `odometer`.
  odometer_sub_ =
      nh.subscribe(publicName("odometer"), 50, &LoopDetectorNodelet::odometerCallback, this);
  // The same metres stamped when measured (bowg_ros/OdometerStamped on
  // `odometer_stamped`): a frame then waits, up to ~odometry_wait, for the
  // reading at its stamp, whatever order the topics arrive in.
  odometer_stamped_sub_ = nh.subscribe(publicName("odometer_stamped"), 50,
                                       &LoopDetectorNodelet::odometerStampedCallback, this);
  odometry_timer_ = nh.createWallTimer(ros::WallDuration(std::max(0.01, odometry_wait_ / 4.0)),
                                       [this](const ros::WallTimerEvent&) {
                                         std::lock_guard<std::mutex> lock(gate_mutex_);
                                         if (odometry_merge_.waiting() > 0) releaseMerged();
                                       });
}

// Odometry, then image (raw or compressed) or upstream features, and
// camera_info.
void LoopDetectorNodelet::subscribeInputs(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  subscribeOdometry(nh);
  // The callbacks only gate
  // and enqueue; the subscriber queues are at least ~queue_size deep so that a
  // large ~queue_size makes a fast bag replay lossless (drops then happen, and
  // are counted, only in our own queue).
  const int input_queue = std::max(5, queue_size_);
  if (use_features_input_) {
    features_sub_ = nh.subscribe(publicName("keyframe_features"), input_queue,
                                 &LoopDetectorNodelet::featuresCallback, this);
  } else if (use_compressed_) {
    // Debian lacks the compressed image_transport plugin: subscribe to the
    // CompressedImage topic directly and decode with greyFromCompressed.
    compressed_sub_ = nh.subscribe(publicName("image") + "/compressed", input_queue,
                                   &LoopDetectorNodelet::compressedCallback, this);
  } else {
    it_.reset(new image_transport::ImageTransport(nh));
    try {
      image_sub_ =
          it_->subscribe(publicName("image"), input_queue, &LoopDetectorNodelet::imageCallback,
                         this, image_transport::TransportHints("raw", ros::TransportHints(), pnh));
    } catch (const std::exception& e) {
      // No input: the diagnostics say so (ERROR) as long as the nodelet lives.
      const std::string problem = "cannot subscribe to " + publicName("image") + ": " + e.what();
      NODELET_FATAL("%s (for compressed input set ~use_compressed)", problem.c_str());
      diagnostics_.inputProblem(problem);
    }
  }
  // Intrinsics (for the relative pose) also in features mode: camera_info is
  // the sibling of the image topic, image_pipeline's convention.
  info_sub_ = nh.subscribe(image_transport::getCameraInfoTopic(publicName("image")), 1,
                           &LoopDetectorNodelet::cameraInfoCallback, this);
}

void LoopDetectorNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  if (!loadParameters(pnh) || !startEngine()) {
    // What a robot's monitoring sees: an ERROR naming the reason, for as
    // long as the nodelet is loaded; a standalone node exits with it.
    reportStartupFailure(getName(), startup_error_);
    startDiagnostics(nh, pnh);
    return;
  }
  gate_.setOptions(gate_options_);
  gate_.setOdometer(lastOdometer(*detector_));
  if (!detector_->database().empty()) gate_.setStampFloor(lastStamp(*detector_));
  queue_.reset(new BoundedQueue<Frame>(static_cast<std::size_t>(queue_size_)));
  diagnostics_.configure(diagnosticsSettings());

  advertiseInterfaces(nh, pnh);
  worker_ = std::thread(&LoopDetectorNodelet::workerLoop, this);
  initialised_ = true;

  // Inputs last, once everything they feed exists.
  subscribeInputs(nh, pnh);
  NODELET_INFO(
      "bowg_ros ready: input %s, keyframe interval %.3f s, distance %.3f m, queue %d",
      use_features_input_ ? publicName("keyframe_features").c_str() : publicName("image").c_str(),
      gate_options_.min_interval, gate_options_.min_distance, queue_size_);
}

}  // namespace bowg_ros

PLUGINLIB_EXPORT_CLASS(bowg_ros::LoopDetectorNodelet, nodelet::Nodelet)
