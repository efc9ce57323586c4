// End-to-end tests of bowg_ros/LoopDetectorNodelet (what a user relies
// on). The .test files start a nodelet manager named bowg_manager; each
// test loads its own nodelet instance into it through the manager's
// load_nodelet service (as bowg_nodelet.launch does), publishes a synthetic
// sequence and watches the outputs. Which tests run is chosen with
// --gtest_filter in the .test file.
#include <mutex>
#include <string>

#include "nodelet_harness.h"

namespace bowg_ros {
namespace {

// The odometry gate end to end: the same revisit with odometry (~odom) that
// puts the robot back at the first pass's places gives loops; with
// odometry that puts it 50 m away (where no earlier keyframe is) it gives
// none, and the keyframe statuses count the candidates the gate removed.
std::vector<cv::Point3d> revisitPositions(double y_of_revisit) {
  std::vector<cv::Point3d> p;
  for (int i = 0; i < kForward; ++i) p.emplace_back(0.1 * i, 0.0, 0.0);
  for (int j = 0; j < kRevisit; ++j) p.emplace_back(0.1 * j, y_of_revisit, 0.0);
  return p;
}

TEST(LoopDetectorNodelet, OdometryGateKeepsLoopsWhereTheOdometryAgrees) {
  const std::map<std::string, XmlRpc::XmlRpcValue> params{{"odometry_gate_m", 0.5},
                                                          {"odometry_gate_drift", 0.0}};
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 1);
  std::size_t agreeing_loops = 0;
  {
    Detector d("/gate_agrees", params);
    ASSERT_TRUE(d.loaded());
    ASSERT_TRUE(d.run(world, test::trajectory(kForward, kRevisit, kStep, kOffset), 1000.0,
                      revisitBrightness(), 25.0, revisitPositions(0.0)));
    ros::WallDuration(0.3).sleep();
    agreeing_loops = d.loops().size();
    EXPECT_GE(agreeing_loops, 5u) << "too few loops where the odometry agrees";
    expectRightIds(d.loops());
  }
  Detector d("/gate_disagrees", params);
  ASSERT_TRUE(d.loaded());
  ASSERT_TRUE(d.run(world, test::trajectory(kForward, kRevisit, kStep, kOffset), 1000.0,
                    revisitBrightness(), 25.0, revisitPositions(50.0)));
  ros::WallDuration(0.3).sleep();
  EXPECT_TRUE(d.loops().empty()) << d.loops().size() << " loops 50 m from the odometry";
  std::uint64_t gated = 0;
  for (const KeyframeStatus& s : d.statuses()) gated += s.candidates_gated;
  EXPECT_GT(gated, 0u);
}

// The loop-anchored gate end to end (odometry_anchor_m, absolute gate
// off): halfway through the revisit the odometry jumps 3 m ahead (a wheel
// slipping on a joint). Without the anchor the loops go on; with it the
// last loop before the jump anchors the robot's place, the second half's
// true places lie 3 m from where the anchor puts them, and they are gated.
std::vector<cv::Point3d> jumpingRevisitPositions() {
  std::vector<cv::Point3d> p = revisitPositions(0.0);
  for (int j = kRevisit / 2; j < kRevisit; ++j) p[kForward + j].x += 3.0;
  return p;
}

std::size_t loopsAfter(const std::vector<LoopClosure>& loops, std::uint32_t first_query) {
  std::size_t n = 0;
  for (const LoopClosure& l : loops) n += l.query_id >= first_query ? 1 : 0;
  return n;
}

TEST(LoopDetectorNodelet, LoopAnchorGatesPlacesTheOdometrySinceTheLastLoopRulesOut) {
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 1);
  const std::uint32_t jump = kForward + kRevisit / 2;
  for (const double anchor_m : {0.0, 0.3}) {
    SCOPED_TRACE(anchor_m);
    Detector d(
        anchor_m > 0.0 ? "/anchor_on" : "/anchor_off",
        {{"odometry_gate_m", 0.0}, {"odometry_gate_drift", 0.0}, {"odometry_anchor_m", anchor_m}});
    ASSERT_TRUE(d.loaded());
    ASSERT_TRUE(d.run(world, test::trajectory(kForward, kRevisit, kStep, kOffset), 1000.0,
                      revisitBrightness(), 25.0, jumpingRevisitPositions()));
    ros::WallDuration(0.3).sleep();
    const std::vector<LoopClosure> loops = d.loops();
    expectRightIds(loops);
    EXPECT_GE(loops.size() - loopsAfter(loops, jump), 1u) << "no loop before the jump";
    std::uint64_t gated = 0;
    for (const KeyframeStatus& s : d.statuses()) gated += s.candidates_gated;
    if (anchor_m > 0.0) {
      EXPECT_EQ(loopsAfter(loops, jump), 0u) << "loops the anchored odometry rules out";
      EXPECT_GT(gated, 0u);
    } else {
      EXPECT_GE(loopsAfter(loops, jump), 3u) << "too few loops after the jump without the anchor";
      EXPECT_EQ(gated, 0u);
    }
  }
}

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

// indexed_per_place end to end: with 1, every keyframe of the revisit that
// closes a loop stays out of the inverse index (its place already has its
// keyframe there), which the diagnostics report beside the database size.
TEST(LoopDetectorNodelet, WithIndexedPerPlaceLoopKeyframesStayOutOfTheIndex) {
  DiagnosticsWatcher diagnostics;
  Detector d("/places", {{"indexed_per_place", XmlRpc::XmlRpcValue(1)}});
  ASSERT_TRUE(d.loaded());
  ASSERT_TRUE(d.connected());
  const cv::Mat world = test::makeWorld(kForward * kStep + kViewWidth + kOffset, kViewHeight, 1);
  ASSERT_TRUE(d.run(world, test::trajectory(kForward, kRevisit, kStep, kOffset), 1000.0,
                    revisitBrightness()));
  ros::WallDuration(0.3).sleep();
  const std::size_t loops = d.loops().size();
  ASSERT_GE(loops, 5u) << "too few loops on a revisit";
  const std::string total = std::to_string(kForward + kRevisit);
  const std::string indexed = std::to_string(kForward + kRevisit - loops);
  // Diagnostics are published once a second: wait for one after the run.
  for (int i = 0; i < 50 && diagnostics.value(d.name(), "database size") != total; ++i)
    ros::WallDuration(0.1).sleep();
  EXPECT_EQ(diagnostics.value(d.name(), "database size"), total);
  EXPECT_EQ(diagnostics.value(d.name(), "keyframes in the inverse index"), indexed);
  // No odometry: no loop has a metric translation, none was ruled out.
  EXPECT_EQ(diagnostics.value(d.name(), "loops with a metric translation"), "0");
  EXPECT_EQ(diagnostics.value(d.name(),
                              "metric translations outside the odometry (published without scale)"),
            "0");
}

/// Median absolute difference of two 8-bit grey images of the same size
/// (robust to the inlier lines drawn over the panels).
int medianAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat d;
  cv::absdiff(a, b, d);
  int histogram[256] = {0};
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x) ++histogram[d.at<std::uint8_t>(y, x)];
  const int half = static_cast<int>(d.total() / 2);
  int count = 0;
  for (int v = 0; v < 256; ++v) {
    count += histogram[v];
    if (count > half) return v;
  }
  return 255;
}

TEST(LoopDetectorNodelet, DebugImageShowsTheMatchOfALoop500KeyframesBack) {
  // Full images of the last 5 keyframes only: the match of a loop 500
  // keyframes back must come from its thumbnail.
  Detector d("/farback", {{"debug_image_cache", 5}});
  ASSERT_TRUE(d.loaded());
  ros::NodeHandle nh;
  std::mutex mutex;
  std::map<double, sensor_msgs::Image> revisit_images;  // by stamp
  const int forward = 500, revisit = 20;
  const double first_stamp = 3000.0;
  ros::Subscriber debug_sub = nh.subscribe<sensor_msgs::Image>(
      d.name() + "/debug_image", 600, [&](const sensor_msgs::Image::ConstPtr& m) {
        if (m->header.stamp.toSec() < first_stamp + 0.1 * forward - 1e-6) return;
        std::lock_guard<std::mutex> lock(mutex);
        revisit_images[m->header.stamp.toSec()] = *m;
      });
  for (int i = 0; i < 100 && debug_sub.getNumPublishers() == 0; ++i)
    ros::WallDuration(0.05).sleep();
  const cv::Mat world = test::makeWorld(forward * kStep + kViewWidth + kOffset, kViewHeight, 21);
  const std::vector<int> xs = test::trajectory(forward, revisit, kStep, kOffset);
  std::vector<int> brightness(forward, 0);
  brightness.resize(forward + revisit, 12);
  ASSERT_TRUE(d.run(world, xs, first_stamp, brightness, 40.0));
  ros::WallDuration(0.5).sleep();
  const std::vector<LoopClosure> loops = d.loops();
  ASSERT_FALSE(loops.empty()) << "no loop on a revisit 500 keyframes back";
  int checked = 0;
  for (const LoopClosure& l : loops) {
    ASSERT_GE(l.query_id - l.match_id, 490u);
    sensor_msgs::Image m;
    {
      std::lock_guard<std::mutex> lock(mutex);
      auto it = revisit_images.find(l.query_stamp.toSec());
      ASSERT_NE(it, revisit_images.end()) << "no debug image for the loop at keyframe "
                                          << l.query_id;
      m = it->second;
    }
    const cv::Mat canvas = cv_bridge::toCvCopy(m, "mono8")->image;
    ASSERT_EQ(canvas.cols, 2 * kViewWidth);
    const int caption = canvas.rows - kViewHeight;
    ASSERT_GT(caption, 0);
    const cv::Mat query = canvas(cv::Rect(0, caption, kViewWidth, kViewHeight));
    const cv::Mat match = canvas(cv::Rect(kViewWidth, caption, kViewWidth, kViewHeight));
    // The right panel is the matched place (from a 240 px JPEG thumbnail:
    // blurred, so compared loosely), not the grey "not cached" panel; the
    // left one is the query (inlier lines drawn over both).
    const cv::Mat true_match = test::viewAt(world, xs[l.match_id], kViewWidth);
    const cv::Mat true_query = test::viewAt(world, xs[l.query_id], kViewWidth, 12);
    const int match_error = medianAbsDiff(match, true_match);
    EXPECT_LT(match_error, 20) << "keyframe " << l.query_id << " -> " << l.match_id;
    // Another place of the strip differs far more: the panel shows this one.
    const cv::Mat elsewhere = test::viewAt(world, xs[l.match_id] + 100 * kStep, kViewWidth);
    EXPECT_GT(medianAbsDiff(match, elsewhere), 2 * match_error + 5);
    EXPECT_LE(medianAbsDiff(query, true_query), 10);
    std::printf("[ MEASURED ] loop %u -> %u: median |debug panel - true view| query %d, match %d, "
                "elsewhere %d\n", l.query_id, l.match_id, medianAbsDiff(query, true_query),
                match_error, medianAbsDiff(match, elsewhere));
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(loops.size()));
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
