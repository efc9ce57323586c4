// End-to-end tests of bowg_ros/LoopDetectorNodelet (what a user relies
// on). The .test files start a nodelet manager named bowg_manager; each
// test loads its own nodelet instance into it through the manager's
// load_nodelet service (as bowg_nodelet.launch does), publishes a synthetic
// sequence and watches the outputs. Which tests run is chosen with
// --gtest_filter in the .test file.
#include <cv_bridge/cv_bridge.h>
#include <dynamic_reconfigure/client.h>
#include <gtest/gtest.h>
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
#include "bowg_ros/LoopClosure.h"
#include "bowg_ros/SaveDatabase.h"
#include "bowg_ros/ros_conversions.h"
#include "synthetic_world.h"
#include "test_vocabulary.h"

namespace bowg_ros {
namespace {

const int kViewWidth = 320, kViewHeight = 240, kStep = 16;
const char kFrame[] = "test_camera_optical_frame";

std::string vocabularyPath() {
  return test::ensureTestVocabulary(std::string(BOWG_TEST_OUTPUT_DIR) +
                                    "/bowg_rostest_vocabulary.bowgvoc");
}

/// One nodelet instance under namespace `ns` (nodelet name ns/bowg), with
/// its inputs and outputs wired to this test.
class Detector {
 public:
  Detector(const std::string& ns, std::map<std::string, XmlRpc::XmlRpcValue> params)
      : ns_(ns), name_(ns + "/bowg") {
    params["vocabulary_path"] = vocabularyPath();
    if (!params.count("queue_size")) params["queue_size"] = 1000;  // no drops in tests
    for (auto& p : params) ros::param::set(name_ + "/" + p.first, p.second);
    image_pub_ = nh_.advertise<sensor_msgs::Image>(ns + "/image", 200);
    info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>(ns + "/camera_info", 200);
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
           (image_pub_.getNumSubscribers() == 0 || info_pub_.getNumSubscribers() == 0 ||
            status_sub_.getNumPublishers() == 0 || loop_sub_.getNumPublishers() == 0)) {
      ros::WallDuration(0.05).sleep();
    }
  }

  ~Detector() {
    nodelet::NodeletUnload unload;
    unload.request.name = name_;
    ros::service::call("/bowg_manager/unload_nodelet", unload);
    ros::param::del(name_);
  }

  bool loaded() const { return loaded_; }
  bool connected() const { return image_pub_.getNumSubscribers() > 0; }
  /// An image message as it comes, whatever its layout.
  void publishRaw(const sensor_msgs::Image& msg) {
    image_pub_.publish(msg);
    ros::WallDuration(0.03).sleep();
  }
  const std::string& name() const { return name_; }

  void publish(const cv::Mat& image, double stamp, const std::string& encoding = "mono8") {
    std_msgs::Header h;
    h.stamp = ros::Time(stamp);
    h.frame_id = kFrame;
    sensor_msgs::CameraInfo info;
    info.header = h;
    info.width = kViewWidth;
    info.height = kViewHeight;
    info.K = {300, 0, kViewWidth / 2.0, 0, 300, kViewHeight / 2.0, 0, 0, 1};
    info_pub_.publish(info);
    image_pub_.publish(cv_bridge::CvImage(h, encoding, image).toImageMsg());
    // Like a camera: frames spaced in time, so the nodelet's subscriber
    // queue never overflows whatever the load of the test machine.
    ros::WallDuration(0.03).sleep();
  }

  /// Publishes the views of `xs` over `world` at ~rate_hz, stamps
  /// first_stamp + 0.1 s per frame, then waits for their keyframe statuses.
  bool run(const cv::Mat& world, const std::vector<int>& xs, double first_stamp,
           const std::vector<int>& brightness = {}, double rate_hz = 25.0) {
    const std::size_t before = statusCount();
    ros::WallRate rate(rate_hz);
    for (std::size_t i = 0; i < xs.size(); ++i) {
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
  ros::Publisher image_pub_, info_pub_;
  ros::Subscriber loop_sub_, status_sub_;
  std::mutex mutex_;
  std::vector<KeyframeStatus> statuses_;
  std::vector<LoopClosure> loops_;
};

// Forward 60 frames, then back to the start for 30 frames, 5 px beside the
// first pass and a little brighter: frame 60 + j revisits the place of frame j.
const int kForward = 60, kRevisit = 30, kOffset = 5;

std::vector<int> revisitBrightness() {
  std::vector<int> b(kForward, 0);
  b.resize(kForward + kRevisit, 12);
  return b;
}

/// Every loop must name the keyframe of the same place (within the island
/// tolerance): match_id ~ query_id - kForward.
void expectRightIds(const std::vector<LoopClosure>& loops) {
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

TEST(LoopDetectorNodelet, RevisitGivesLoopClosuresWithTheRightIds) {
  Detector d("/revisit", {});
  ASSERT_TRUE(d.loaded());
  ASSERT_TRUE(d.connected());
  ros::NodeHandle nh;
  DebugImages debug;
  ros::Subscriber debug_sub =
      nh.subscribe(d.name() + "/debug_image", 200, &DebugImages::on, &debug);
  for (int i = 0; i < 100 && debug_sub.getNumPublishers() == 0; ++i)
    ros::WallDuration(0.05).sleep();
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 1);
  ASSERT_TRUE(d.run(world, test::trajectory(kForward, kRevisit, kStep, kOffset), 1000.0,
                    revisitBrightness()));
  ros::WallDuration(0.3).sleep();  // loop messages trail the last status
  const std::vector<LoopClosure> loops = d.loops();
  ASSERT_GE(loops.size(), 5u) << "too few loops on a revisit";
  expectRightIds(loops);
  const LoopClosure& l = loops.front();
  EXPECT_EQ(l.header.frame_id, kFrame);
  EXPECT_DOUBLE_EQ(l.query_stamp.toSec(), 1000.0 + 0.1 * l.query_id);
  EXPECT_DOUBLE_EQ(l.match_stamp.toSec(), 1000.0 + 0.1 * l.match_id);
  EXPECT_LE(l.island_first, l.match_id);
  EXPECT_GE(l.island_last, l.match_id);
  EXPECT_GE(l.inliers, 15u);
  EXPECT_TRUE(l.has_relative_pose);  // camera_info was published
  EXPECT_FALSE(l.translation_scale_known);
  EXPECT_EQ(l.relative_pose.covariance[0], LoopClosure::UNOBSERVABLE_SCALE_VARIANCE);
  // One status per keyframe, ids in order, loops flagged in the status too.
  const std::vector<KeyframeStatus> s = d.statuses();
  ASSERT_EQ(s.size(), static_cast<std::size_t>(kForward + kRevisit));
  std::size_t flagged = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_EQ(s[i].id, i);
    EXPECT_EQ(s[i].database_size, i + 1);
    EXPECT_GT(s[i].num_features, 50u);
    if (s[i].status == KeyframeStatus::LOOP_DETECTED) ++flagged;
  }
  EXPECT_EQ(flagged, loops.size());
  // The debug image (drawn because we subscribe): query | match, caption on top.
  {
    std::lock_guard<std::mutex> lock(debug.mutex);
    EXPECT_GE(debug.count, kForward);
    EXPECT_EQ(debug.last.encoding, "bgr8");
    EXPECT_EQ(debug.last.width, 2u * kViewWidth);
    EXPECT_GT(debug.last.height, static_cast<std::uint32_t>(kViewHeight));
  }
  // Measured numbers for the record (not asserted: machine dependent).
  double total = 0, features = 0, worst = 0;
  for (const KeyframeStatus& k : s) {
    total += k.total_ms;
    features += k.feature_ms;
    worst = std::max(worst, k.total_ms);
  }
  std::printf(
      "[ MEASURED ] %zu keyframes 320x240: mean %.2f ms/keyframe (features %.2f ms), "
      "max %.2f ms; %zu loops\n",
      s.size(), total / s.size(), features / s.size(), worst, loops.size());
  // rostest keeps the node's stdout to itself: record in the result XML too.
  RecordProperty("mean_keyframe_ms", std::to_string(total / s.size()));
  RecordProperty("mean_feature_ms", std::to_string(features / s.size()));
  RecordProperty("max_keyframe_ms", std::to_string(worst));
  RecordProperty("loops", std::to_string(loops.size()));
}

TEST(LoopDetectorNodelet, NonRevisitingSequenceGivesNoLoop) {
  Detector d("/forward", {});
  ASSERT_TRUE(d.loaded());
  const int n = kForward + kRevisit;
  const cv::Mat world = test::makeWorld(n * kStep + kViewWidth, kViewHeight, 2);
  ASSERT_TRUE(d.run(world, test::trajectory(n, 0, kStep, 0), 1000.0));
  ros::WallDuration(0.3).sleep();
  EXPECT_EQ(d.loops().size(), 0u);
  EXPECT_EQ(d.statusCount(), static_cast<std::size_t>(n));
}

/// Collects ERROR log lines from /rosout.
class ErrorLog {
 public:
  ErrorLog() { sub_ = nh_.subscribe("/rosout", 100, &ErrorLog::onLog, this); }
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
    if (m->level < rosgraph_msgs::Log::ERROR) return;
    std::lock_guard<std::mutex> lock(mutex_);
    errors_.push_back(m->msg);
  }
  ros::NodeHandle nh_;
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::vector<std::string> errors_;
};

TEST(LoopDetectorNodelet, MalformedImagesAreReportedAndTheNodeletKeepsRunning) {
  ErrorLog log;
  Detector d("/malformed", {});
  ASSERT_TRUE(d.loaded());
  ros::WallDuration(0.5).sleep();  // /rosout connection
  // mono8, 64 x 48, step 64, but only 100 bytes of data: a reader of
  // height x step bytes would run past the buffer.
  sensor_msgs::Image bad;
  bad.header.stamp = ros::Time(500.0);
  bad.header.frame_id = kFrame;
  bad.width = 64;
  bad.height = 48;
  bad.step = 64;
  bad.encoding = "mono8";
  bad.data.assign(100, 0);
  d.publishRaw(bad);
  EXPECT_TRUE(log.waitFor("malformed image at 500.000000", 10.0)) << "no error for the image";
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 3);
  d.publish(test::viewAt(world, 0, kViewWidth), 501.0);
  EXPECT_TRUE(d.waitForStatuses(1, 20.0)) << "the nodelet stopped after a malformed image";
}

TEST(LoopDetectorNodelet, BadImageIsReportedAndTheNodeletKeepsRunning) {
  ErrorLog log;
  Detector d("/encoding", {});
  ASSERT_TRUE(d.loaded());
  ros::WallDuration(0.5).sleep();  // /rosout connection
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 3);
  cv::Mat depth(kViewHeight, kViewWidth, CV_32FC1, cv::Scalar(1.5f));
  d.publish(depth, 999.0, "32FC1");
  EXPECT_TRUE(log.waitFor("'32FC1'", 10.0)) << "no error naming the encoding";
  // Still alive: every supported encoding gives a keyframe status.
  const cv::Mat view = test::viewAt(world, 0, kViewWidth);
  cv::Mat bgr, rgba, mono16;
  cv::cvtColor(view, bgr, cv::COLOR_GRAY2BGR);
  cv::cvtColor(view, rgba, cv::COLOR_GRAY2RGBA);
  view.convertTo(mono16, CV_16U, 256.0);
  d.publish(view, 1000.0, "mono8");
  d.publish(mono16, 1000.1, "mono16");
  d.publish(bgr, 1000.2, "bgr8");
  d.publish(bgr, 1000.3, "rgb8");
  d.publish(rgba, 1000.4, "rgba8");
  d.publish(rgba, 1000.5, "bgra8");
  ASSERT_TRUE(d.waitForStatuses(6, 20.0));
  const std::vector<KeyframeStatus> s = d.statuses();
  ASSERT_EQ(s.size(), 6u);
  // The grey conversions agree up to rounding, so the features do too.
  for (const KeyframeStatus& k : s) {
    EXPECT_NEAR(static_cast<double>(k.num_features), s[0].num_features, 0.1 * s[0].num_features);
  }
  // A repeated and an older stamp are skipped (no status).
  d.publish(view, 1000.5, "mono8");
  d.publish(view, 900.0, "mono8");
  d.publish(view, 1001.0, "mono8");
  ASSERT_TRUE(d.waitForStatuses(7, 20.0));
  ros::WallDuration(0.3).sleep();
  EXPECT_EQ(d.statusCount(), 7u);
  EXPECT_DOUBLE_EQ(d.statuses().back().header.stamp.toSec(), 1001.0);
}

TEST(LoopDetectorNodelet, CompressedAndFeatureInputsAreProcessed) {
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 6);
  const cv::Mat view = test::viewAt(world, 0, kViewWidth);
  ros::NodeHandle nh;
  {
    // ~use_compressed: sensor_msgs/CompressedImage on <image>/compressed.
    Detector d("/compressed", {{"use_compressed", XmlRpc::XmlRpcValue(true)}});
    ASSERT_TRUE(d.loaded());
    ros::Publisher pub =
        nh.advertise<sensor_msgs::CompressedImage>("/compressed/image/compressed", 10);
    for (int i = 0; i < 100 && pub.getNumSubscribers() == 0; ++i) ros::WallDuration(0.05).sleep();
    sensor_msgs::CompressedImage m;
    m.header.stamp = ros::Time(1000.0);
    m.header.frame_id = kFrame;
    m.format = "png";
    cv::imencode(".png", view, m.data);
    pub.publish(m);
    ASSERT_TRUE(d.waitForStatuses(1, 20.0));
    EXPECT_GT(d.statuses()[0].num_features, 50u);
  }
  {
    // ~use_features_input: bowg_ros/KeyframeFeatures from an upstream front end.
    Detector d("/features", {{"use_features_input", XmlRpc::XmlRpcValue(true)}});
    ASSERT_TRUE(d.loaded());
    ros::Publisher pub = nh.advertise<KeyframeFeatures>("/features/keyframe_features", 10);
    for (int i = 0; i < 100 && pub.getNumSubscribers() == 0; ++i) ros::WallDuration(0.05).sleep();
    const bowg::ImageFeatures f = bowg::FeatureExtractor(bowg::FeatureOptions()).extract(view);
    std_msgs::Header h;
    h.stamp = ros::Time(1000.0);
    pub.publish(toMessage(f, h));
    ASSERT_TRUE(d.waitForStatuses(1, 20.0));
    EXPECT_EQ(d.statuses()[0].num_features, f.size());
    EXPECT_EQ(d.statuses()[0].feature_ms, 0.0);  // no extraction in the nodelet
  }
}

TEST(LoopDetectorNodelet, OnlyFramesPastTheMinimumIntervalBecomeKeyframes) {
  Detector d("/gate", {{"min_keyframe_interval", XmlRpc::XmlRpcValue(0.25)}});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 7);
  // Stamps 1000.0, 1000.1, ... 1000.9: keyframes at 1000.0, 1000.3, 1000.6,
  // 1000.9 (each the first frame >= 0.25 s after the previous keyframe).
  for (int i = 0; i < 10; ++i)
    d.publish(test::viewAt(world, i * kStep, kViewWidth), 1000.0 + 0.1 * i);
  ASSERT_TRUE(d.waitForStatuses(4, 20.0));
  ros::WallDuration(0.5).sleep();
  const std::vector<KeyframeStatus> s = d.statuses();
  ASSERT_EQ(s.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(s[k].header.stamp.toSec(), 1000.0 + 0.3 * k, 1e-6);
}

bool setConfig(const std::string& node, BoWGConfig* config) {
  dynamic_reconfigure::Client<BoWGConfig> client(node);
  return client.setConfiguration(*config);
}

TEST(LoopDetectorNodelet, LiveParametersTakeEffectAndInvalidValuesAreCorrected) {
  Detector d("/tuning", {});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 4);
  const std::vector<int> xs = test::trajectory(kForward, kRevisit, kStep, kOffset);

  BoWGConfig c = BoWGConfig::__getDefault__();
  c.lambda_1 = 0.65;
  c.lambda_2 = 0.25;
  c.w_max = 0.4;
  c.alpha = 0.3;
  c.fan_bins = 12;
  c.min_score = 0.25;
  c.temporal_k = 2;
  c.min_inliers = 20;
  c.direct_index_level = 2;
  c.word_groups = false;
  c.distribution = true;
  c.temporal_score = false;
  c.geometric_verification = true;
  c.exhaustive_matching = true;
  ASSERT_TRUE(setConfig(d.name(), &c));
  d.publish(test::viewAt(world, 0, kViewWidth), 1000.0);
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  KeyframeStatus s = d.statuses().back();
  // Each live parameter is in force from the next keyframe.
  EXPECT_EQ(s.lambda_1, 0.65);
  EXPECT_EQ(s.lambda_2, 0.25);
  EXPECT_EQ(s.w_max, 0.4);
  EXPECT_EQ(s.alpha, 0.3);
  EXPECT_EQ(s.fan_bins, 12);
  EXPECT_EQ(s.min_score, 0.25);
  EXPECT_EQ(s.temporal_k, 2);
  EXPECT_EQ(s.min_inliers, 20);
  EXPECT_EQ(s.direct_index_level, 2);
  EXPECT_FALSE(s.word_groups);
  EXPECT_TRUE(s.distribution);
  EXPECT_FALSE(s.temporal_score);
  EXPECT_TRUE(s.geometric_verification);
  EXPECT_TRUE(s.exhaustive_matching);

  // Invalid combinations are corrected and the client gets the corrected
  // values: 0.8 + 0.5 > 1 -> lambda_2 = 1 - 0.8 = 0.2; level 9 deeper than
  // the test vocabulary's L = 3 -> 3.
  c.lambda_1 = 0.8;
  c.lambda_2 = 0.5;
  c.direct_index_level = 9;
  ASSERT_TRUE(setConfig(d.name(), &c));
  EXPECT_NEAR(c.lambda_2, 0.2, 1e-12);
  EXPECT_EQ(c.direct_index_level, 3);
  d.publish(test::viewAt(world, kStep, kViewWidth), 1000.1);
  ASSERT_TRUE(d.waitForStatuses(2, 20.0));
  s = d.statuses().back();
  EXPECT_NEAR(s.lambda_2, 0.2, 1e-12);
  EXPECT_EQ(s.direct_index_level, 3);

  // The same through the command line users type (dynparam set).
  const std::string cmd = "rosrun dynamic_reconfigure dynparam set " + d.name() +
                          " \"{'lambda_1': 0.9, 'lambda_2': 0.9}\" > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  d.publish(test::viewAt(world, 2 * kStep, kViewWidth), 1000.2);
  ASSERT_TRUE(d.waitForStatuses(3, 20.0));
  s = d.statuses().back();
  EXPECT_NEAR(s.lambda_1, 0.9, 1e-12);
  EXPECT_NEAR(s.lambda_2, 0.1, 1e-9);

  // Effects on the scores: with the distribution score off, eq. 5 with
  // lambda_1 = 1 gives eta_sim = eta_w; with the temporal score off
  // eta = eta_sim; with min_score = 10 no loop is accepted on a revisit.
  c = BoWGConfig::__getDefault__();
  c.distribution = false;
  c.lambda_1 = 1.0;
  c.temporal_score = false;
  c.min_score = 10.0;
  ASSERT_TRUE(setConfig(d.name(), &c));
  d.clear();
  const std::vector<int> rest(xs.begin() + 3, xs.end());
  const std::vector<int> light = revisitBrightness();
  ASSERT_TRUE(d.run(world, rest, 1000.3, std::vector<int>(light.begin() + 3, light.end())));
  std::size_t with_candidate = 0;
  for (const KeyframeStatus& k : d.statuses()) {
    EXPECT_NE(k.status, KeyframeStatus::LOOP_DETECTED) << "min_score = 10 accepted a loop";
    if (!k.has_candidate) continue;
    ++with_candidate;
    EXPECT_NEAR(k.best_score_sim, k.best_score_word, 1e-9);
    EXPECT_NEAR(k.best_score, k.best_score_sim, 1e-9);
  }
  EXPECT_GT(with_candidate, 10u);
  EXPECT_TRUE(d.loops().empty());

  // Back to an accepting threshold: the database survived every change, so
  // revisiting the first places again finds loops at once.
  c.min_score = 0.3;
  c.lambda_1 = 0.5;
  c.temporal_score = true;
  ASSERT_TRUE(setConfig(d.name(), &c));
  d.clear();
  std::vector<int> again;
  for (int j = 0; j < 20; ++j) again.push_back(j * kStep + 2);
  ASSERT_TRUE(d.run(world, again, 1020.0));
  ros::WallDuration(0.3).sleep();
  EXPECT_FALSE(d.loops().empty()) << "database lost after reconfiguration";
}

TEST(LoopDetectorNodelet, SaveResetLoadRestoresDetectionAndCorruptLoadKeepsTheDatabase) {
  Detector d("/persistence", {});
  ASSERT_TRUE(d.loaded());
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 5);
  const std::vector<int> xs = test::trajectory(kForward, kRevisit, kStep, kOffset);
  const std::vector<int> first(xs.begin(), xs.begin() + kForward);
  const std::vector<int> second(xs.begin() + kForward, xs.end());
  ASSERT_TRUE(d.run(world, first, 1000.0));

  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_rostest_database.bin";
  std::remove(path.c_str());
  SaveDatabase save;
  save.request.path = path;
  ASSERT_TRUE(ros::service::call(d.name() + "/save_database", save));
  EXPECT_TRUE(save.response.success) << save.response.message;
  EXPECT_EQ(access(path.c_str(), R_OK), 0);

  std_srvs::Trigger reset;
  ASSERT_TRUE(ros::service::call(d.name() + "/reset", reset));
  EXPECT_TRUE(reset.response.success);
  // After the reset the revisit finds nothing: the first pass is forgotten.
  d.clear();
  ASSERT_TRUE(d.run(world, second, 2000.0, std::vector<int>(kRevisit, 12)));
  ros::WallDuration(0.3).sleep();
  EXPECT_TRUE(d.loops().empty());
  EXPECT_EQ(d.statuses().front().database_size, 1u);

  // A corrupt file fails with a message and keeps the running database.
  const std::string corrupt = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_rostest_corrupt.bin";
  std::ofstream(corrupt) << "this is not a BoWG database";
  LoadDatabase load;
  load.request.path = corrupt;
  ASSERT_TRUE(ros::service::call(d.name() + "/load_database", load));
  EXPECT_FALSE(load.response.success);
  EXPECT_NE(load.response.message.find(corrupt), std::string::npos) << load.response.message;
  d.clear();
  d.publish(test::viewAt(world, 0, kViewWidth), 2100.0);
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  EXPECT_EQ(d.statuses().back().database_size, static_cast<std::uint32_t>(kRevisit + 1));

  // Loading the saved file restores the first pass: the revisit finds loops
  // with the first pass's ids again.
  reset = std_srvs::Trigger();
  ASSERT_TRUE(ros::service::call(d.name() + "/reset", reset));
  load.request.path = path;
  ASSERT_TRUE(ros::service::call(d.name() + "/load_database", load));
  EXPECT_TRUE(load.response.success) << load.response.message;
  d.clear();
  ASSERT_TRUE(d.run(world, second, 3000.0, std::vector<int>(kRevisit, 12)));
  ros::WallDuration(0.3).sleep();
  const std::vector<KeyframeStatus> s = d.statuses();
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s.front().id, static_cast<std::uint32_t>(kForward));  // ids continue the file's
  const std::vector<LoopClosure> loops = d.loops();
  EXPECT_GE(loops.size(), 5u) << "no detection after load";
  expectRightIds(loops);
}

TEST(LoopDetectorNodelet, DatabaseIsSavedAtShutdownAndLoadedAtStart) {
  const std::string path = std::string(BOWG_TEST_OUTPUT_DIR) + "/bowg_rostest_shutdown.bin";
  std::remove(path.c_str());
  const cv::Mat world = test::makeWorld(kViewWidth + 10 * kStep, kViewHeight, 8);
  {
    Detector d("/shutdown", {{"database_save_path", XmlRpc::XmlRpcValue(path)}});
    ASSERT_TRUE(d.loaded());
    for (int i = 0; i < 3; ++i) d.publish(test::viewAt(world, i * kStep, kViewWidth), 1000.0 + i);
    ASSERT_TRUE(d.waitForStatuses(3, 20.0));
  }  // unloading the nodelet saves
  EXPECT_EQ(access(path.c_str(), R_OK), 0) << "not saved at shutdown";
  Detector d("/startup", {{"database_load_path", XmlRpc::XmlRpcValue(path)}});
  ASSERT_TRUE(d.loaded());
  d.publish(test::viewAt(world, 5 * kStep, kViewWidth), 2000.0);
  ASSERT_TRUE(d.waitForStatuses(1, 20.0));
  EXPECT_EQ(d.statuses()[0].id, 3u);
  EXPECT_EQ(d.statuses()[0].database_size, 4u);
}

}  // namespace
}  // namespace bowg_ros

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "bowg_loop_detector_rostest");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  // Train the vocabulary before any nodelet needs it.
  bowg_ros::vocabularyPath();
  return RUN_ALL_TESTS();
}
