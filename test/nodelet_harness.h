// The harness of the nodelet's end-to-end tests (loop_detector_rostest.cpp,
// nodelet_tuning_rostest.cpp): one nodelet instance loaded into the test's
// manager with its inputs and outputs wired to the test, the synthetic
// revisit sequence, an /rosout error collector and the live-tuning client.
#pragma once

#include <cv_bridge/cv_bridge.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/client.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/NodeletLoad.h>
#include <nodelet/NodeletUnload.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "bowg/features/feature_extractor.h"
#include "bowg_ros/BoWGConfig.h"
#include "bowg_ros/KeyframeFeatures.h"
#include "bowg_ros/KeyframeStatus.h"
#include "bowg_ros/LoadDatabase.h"
#include "bowg_ros/LoadReferenceMaps.h"
#include "bowg_ros/LoopClosure.h"
#include "bowg_ros/MergeDatabases.h"
#include "bowg_ros/SaveDatabase.h"
#include "bowg_ros/ros_conversions.h"
#include "encoded_test_images.h"
#include "synthetic_world.h"
#include "test_vocabulary.h"

namespace bowg_ros {

const int kViewWidth = 320, kViewHeight = 240, kStep = 16;
const char kFrame[] = "test_camera_optical_frame";

inline std::string vocabularyPath() {
  return test::ensureTestVocabulary(std::string(BOWG_TEST_OUTPUT_DIR) +
                                    "/bowg_rostest_vocabulary.bowgvoc");
}

/// The intrinsics of the synthetic views (f = 300 px, centred).
inline sensor_msgs::CameraInfo viewCameraInfo(const std_msgs::Header& h) {
  sensor_msgs::CameraInfo info;
  info.header = h;
  info.width = kViewWidth;
  info.height = kViewHeight;
  info.K = {300, 0, kViewWidth / 2.0, 0, 300, kViewHeight / 2.0, 0, 0, 1};
  return info;
}

/// One nodelet instance under namespace `ns` (nodelet name ns/bowg), with
/// its inputs and outputs wired to this test.
class Detector {
 public:
  Detector(const std::string& ns, std::map<std::string, XmlRpc::XmlRpcValue> params)
      : ns_(ns), name_(ns + "/bowg") {
    if (!params.count("vocabulary_path")) params["vocabulary_path"] = vocabularyPath();
    if (!params.count("queue_size")) params["queue_size"] = 1000;  // no drops in tests
    compressed_ = params.count("use_compressed") && bool(params["use_compressed"]);
    for (auto& p : params) ros::param::set(name_ + "/" + p.first, p.second);
    image_pub_ = nh_.advertise<sensor_msgs::Image>(ns + "/image", 200);
    compressed_pub_ = nh_.advertise<sensor_msgs::CompressedImage>(ns + "/image/compressed", 200);
    info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>(ns + "/camera_info", 200);
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>(ns + "/odom", 200);
    loop_sub_ = nh_.subscribe(ns + "/loop_closure", 200, &Detector::onLoop, this);
    status_sub_ = nh_.subscribe(name_ + "/keyframe_status", 1000, &Detector::onStatus, this);

    nodelet::NodeletLoad load;
    load.request.name = name_;
    load.request.type = "bowg_ros/LoopDetectorNodelet";
    loaded_ = ros::service::waitForService("/bowg_manager/load_nodelet", ros::Duration(30)) &&
              ros::service::call("/bowg_manager/load_nodelet", load) && load.response.success;
    // Wait until the nodelet is connected both ways.
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20);
    while (loaded_ && ros::WallTime::now() < end &&
           ((compressed_ ? compressed_pub_ : image_pub_).getNumSubscribers() == 0 ||
            info_pub_.getNumSubscribers() == 0 || odom_pub_.getNumSubscribers() == 0 ||
            status_sub_.getNumPublishers() == 0 || loop_sub_.getNumPublishers() == 0)) {
      ros::WallDuration(0.05).sleep();
    }
  }

  ~Detector() {
    if (loaded_) unload();
    ros::param::del(name_);
  }

  /// Unloads the nodelet from the manager (also done on destruction); true
  /// when the manager unloaded it.
  bool unload() {
    nodelet::NodeletUnload unload;
    unload.request.name = name_;
    loaded_ = false;
    return ros::service::call("/bowg_manager/unload_nodelet", unload) && unload.response.success;
  }

  bool loaded() const { return loaded_; }
  bool connected() const { return image_pub_.getNumSubscribers() > 0; }
  /// An image message as it comes, whatever its layout.
  void publishRaw(const sensor_msgs::Image& msg) {
    image_pub_.publish(msg);
    ros::WallDuration(0.03).sleep();
  }
  /// A CompressedImage (on ns/image/compressed, for ~use_compressed) of
  /// whatever bytes `data` holds.
  void publishCompressed(const std::vector<std::uint8_t>& data, double stamp) {
    sensor_msgs::CompressedImage msg;
    msg.header.stamp = ros::Time(stamp);
    msg.header.frame_id = kFrame;
    msg.format = "png";
    msg.data = data;
    compressed_pub_.publish(msg);
    ros::WallDuration(0.03).sleep();
  }
  const std::string& name() const { return name_; }

  void publish(const cv::Mat& image, double stamp, const std::string& encoding = "mono8") {
    std_msgs::Header h;
    h.stamp = ros::Time(stamp);
    h.frame_id = kFrame;
    info_pub_.publish(viewCameraInfo(h));
    image_pub_.publish(cv_bridge::CvImage(h, encoding, image).toImageMsg());
    // Like a camera: frames spaced in time, so the nodelet's subscriber
    // queue never overflows whatever the load of the test machine.
    ros::WallDuration(0.03).sleep();
  }

  /// A camera_info alone (a camera whose images go elsewhere).
  void publishCameraInfo(double stamp) {
    std_msgs::Header h;
    h.stamp = ros::Time(stamp);
    h.frame_id = kFrame;
    info_pub_.publish(viewCameraInfo(h));
  }

  /// The robot's odometry position (nav_msgs/Odometry on ns/odom), given
  /// time to arrive before the next image.
  void publishOdometry(const cv::Point3d& p, double stamp) {
    nav_msgs::Odometry o;
    o.header.stamp = ros::Time(stamp);
    o.header.frame_id = "odom";
    o.pose.pose.position.x = p.x;
    o.pose.pose.position.y = p.y;
    o.pose.pose.position.z = p.z;
    o.pose.pose.orientation.w = 1.0;
    odom_pub_.publish(o);
    ros::WallDuration(0.03).sleep();
  }

  /// Publishes the views of `xs` over `world` at ~rate_hz, stamps
  /// first_stamp + 0.1 s per frame (each after its odometry position when
  /// `positions` are given), then waits for their keyframe statuses.
  bool run(const cv::Mat& world, const std::vector<int>& xs, double first_stamp,
           const std::vector<int>& brightness = {}, double rate_hz = 25.0,
           const std::vector<cv::Point3d>& positions = {}) {
    const std::size_t before = statusCount();
    ros::WallRate rate(rate_hz);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      if (!positions.empty()) publishOdometry(positions[i], first_stamp + 0.1 * i);
      publish(test::viewAt(world, xs[i], kViewWidth, brightness.empty() ? 0 : brightness[i]),
              first_stamp + 0.1 * i);
      rate.sleep();
    }
    return waitForStatuses(before + xs.size(), 60.0);
  }

  bool waitForStatuses(std::size_t n, double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (statusCount() < n && ros::WallTime::now() < end) ros::WallDuration(0.02).sleep();
    return statusCount() >= n;
  }

  std::size_t statusCount() {
    std::lock_guard<std::mutex> lock(mutex_);
    return statuses_.size();
  }
  std::vector<KeyframeStatus> statuses() {
    std::lock_guard<std::mutex> lock(mutex_);
    return statuses_;
  }
  std::vector<LoopClosure> loops() {
    std::lock_guard<std::mutex> lock(mutex_);
    return loops_;
  }
  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    statuses_.clear();
    loops_.clear();
  }

 private:
  void onLoop(const LoopClosure::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    loops_.push_back(*m);
  }
  void onStatus(const KeyframeStatus::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    statuses_.push_back(*m);
  }

  ros::NodeHandle nh_;
  std::string ns_, name_;
  bool loaded_ = false;
  bool compressed_ = false;  ///< ~use_compressed: images go to ns/image/compressed
  ros::Publisher image_pub_, compressed_pub_, info_pub_, odom_pub_;
  ros::Subscriber loop_sub_, status_sub_;
  std::mutex mutex_;
  std::vector<KeyframeStatus> statuses_;
  std::vector<LoopClosure> loops_;
};

// Forward 60 frames, then back to the start for 30 frames, 5 px beside the
// first pass and a little brighter: frame 60 + j revisits the place of frame j.
const int kForward = 60, kRevisit = 30, kOffset = 5;

inline std::vector<int> revisitBrightness() {
  std::vector<int> b(kForward, 0);
  b.resize(kForward + kRevisit, 12);
  return b;
}

/// Every loop must name the keyframe of the same place (within the island
/// tolerance): match_id ~ query_id - kForward.
inline void expectRightIds(const std::vector<LoopClosure>& loops) {
  for (const LoopClosure& l : loops) {
    EXPECT_GE(l.query_id, static_cast<std::uint32_t>(kForward));
    EXPECT_NEAR(static_cast<double>(l.match_id), static_cast<double>(l.query_id) - kForward, 3.0)
        << "query " << l.query_id << " matched " << l.match_id;
  }
}

/// Counts ~debug_image messages and remembers the last one's size.
struct DebugImages {
  std::mutex mutex;
  int count = 0;
  sensor_msgs::Image last;
  void on(const sensor_msgs::Image::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    ++count;
    last = *m;
  }
};

/// Collects log lines from /rosout at `min_level` or above (ERROR unless
/// told otherwise).
class ErrorLog {
 public:
  explicit ErrorLog(std::uint8_t min_level = rosgraph_msgs::Log::ERROR) : min_level_(min_level) {
    sub_ = nh_.subscribe("/rosout", 100, &ErrorLog::onLog, this);
  }
  bool waitFor(const std::string& text, double timeout) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::WallTime::now() < end) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const std::string& l : errors_) {
          if (l.find(text) != std::string::npos) return true;
        }
      }
      ros::WallDuration(0.05).sleep();
    }
    return false;
  }

 private:
  void onLog(const rosgraph_msgs::Log::ConstPtr& m) {
    if (m->level < min_level_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    errors_.push_back(m->msg);
  }
  std::uint8_t min_level_;
  ros::NodeHandle nh_;
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::vector<std::string> errors_;
};

/// The latest /diagnostics status of each nodelet, by status name
/// ("<nodelet name without the leading slash>: loop detector").
class DiagnosticsWatcher {
 public:
  DiagnosticsWatcher() { sub_ = nh_.subscribe("/diagnostics", 50, &DiagnosticsWatcher::on, this); }
  /// Waits until the status of `nodelet` (e.g. "/gate/bowg") has `level`
  /// and its message contains `text`; returns whether it did. `last` gets
  /// the latest status seen (for failure messages).
  bool waitFor(const std::string& nodelet, std::uint8_t level, const std::string& text,
               double timeout, diagnostic_msgs::DiagnosticStatus* last) {
    const std::string name = nodelet.substr(1) + ": loop detector";
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::WallTime::now() < end) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = latest_.find(name);
        if (it != latest_.end()) {
          *last = it->second;
          if (it->second.level == level && it->second.message.find(text) != std::string::npos)
            return true;
        }
      }
      ros::WallDuration(0.1).sleep();
    }
    return false;
  }
  /// The value of `key` in the latest status of `nodelet` ("" if none).
  std::string value(const std::string& nodelet, const std::string& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = latest_.find(nodelet.substr(1) + ": loop detector");
    if (it == latest_.end()) return "";
    for (const auto& kv : it->second.values) {
      if (kv.key == key) return kv.value;
    }
    return "";
  }

 private:
  void on(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& st : msg->status) latest_[st.name] = st;
  }
  ros::NodeHandle nh_;
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> latest_;
};

inline bool setConfig(const std::string& node, BoWGConfig* config) {
  dynamic_reconfigure::Client<BoWGConfig> client(node);
  return client.setConfiguration(*config);
}

}  // namespace bowg_ros
