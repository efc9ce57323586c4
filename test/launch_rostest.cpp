// End-to-end tests of the launch files as the README uses them
// (test/launch_files.test starts them): bowg_nodelet.launch into a camera
// driver's manager that lives in its own namespace, at the root and under
// `ns`, and bowg.launch with its own manager under `ns`, all with the bundled
// default vocabulary. Each nodelet must subscribe to the topic its `image`
// argument names, publish loop_closure in its own namespace and answer an
// image with a keyframe status.
#include <ros/master.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <map>
#include <mutex>
#include <set>
#include <string>

#include "nodelet_harness.h"

namespace bowg_ros {
namespace {

struct TopicEnds {
  std::set<std::string> publishers, subscribers;  // node names
};

/// The master's view: topic -> publishing and subscribing nodes.
std::map<std::string, TopicEnds> systemState() {
  std::map<std::string, TopicEnds> topics;
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, payload, true)) return topics;
  for (int kind = 0; kind < 2; ++kind) {
    XmlRpc::XmlRpcValue& list = payload[kind];
    for (int i = 0; i < list.size(); ++i) {
      const std::string topic = list[i][0];
      for (int j = 0; j < list[i][1].size(); ++j) {
        const std::string node = list[i][1][j];
        (kind == 0 ? topics[topic].publishers : topics[topic].subscribers).insert(node);
      }
    }
  }
  return topics;
}

/// Waits until `topic` has a publisher (or a subscriber) on the master.
bool waitForEnd(const std::string& topic, bool publisher, double timeout) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::WallTime::now() < end) {
    const auto topics = systemState();
    auto it = topics.find(topic);
    if (it != topics.end() &&
        !(publisher ? it->second.publishers : it->second.subscribers).empty())
      return true;
    ros::WallDuration(0.1).sleep();
  }
  return false;
}

/// Collects the keyframe statuses of one nodelet.
struct StatusCounter {
  std::mutex mutex;
  int count = 0;
  void on(const KeyframeStatus::ConstPtr&) {
    std::lock_guard<std::mutex> lock(mutex);
    ++count;
  }
  int get() {
    std::lock_guard<std::mutex> lock(mutex);
    return count;
  }
};

/// Publishes textured images (and camera_info) on `image_topic` until every
/// counter saw a status or `timeout` s passed; true when all did.
bool imagesReachEveryNodelet(const std::string& image_topic,
                             const std::vector<StatusCounter*>& counters, double timeout) {
  ros::NodeHandle nh;
  ros::Publisher image_pub = nh.advertise<sensor_msgs::Image>(image_topic, 10);
  ros::Publisher info_pub = nh.advertise<sensor_msgs::CameraInfo>(
      ros::names::parentNamespace(image_topic) + "/camera_info", 10);
  const cv::Mat world = test::makeWorld(kViewWidth + 40 * kStep, kViewHeight, 11);
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  for (int i = 0; ros::WallTime::now() < end; ++i) {
    bool all = true;
    for (StatusCounter* c : counters) all = all && c->get() > 0;
    if (all) return true;
    std_msgs::Header h;
    h.stamp = ros::Time(2000.0 + 0.1 * i);
    h.frame_id = kFrame;
    info_pub.publish(viewCameraInfo(h));
    image_pub.publish(cv_bridge::CvImage(h, "mono8",
                                         test::viewAt(world, (i % 40) * kStep, kViewWidth))
                          .toImageMsg());
    ros::WallDuration(0.2).sleep();
  }
  return false;
}

TEST(LaunchFiles, NodeletsInANamespacedManagerUseTheirOwnNamespaceAndTheImageRemap) {
  // The camera's manager is /camera/camera_nodelet_manager; /bowg (the
  // README's command) and /robot/bowg are loaded into it.
  ASSERT_TRUE(waitForEnd("/loop_closure", true, 60.0)) << "/bowg advertised no /loop_closure";
  ASSERT_TRUE(waitForEnd("/robot/loop_closure", true, 60.0))
      << "/robot/bowg advertised no /robot/loop_closure";
  ASSERT_TRUE(waitForEnd("/camera/image_raw", false, 60.0));
  ros::WallDuration(1.0).sleep();  // both nodelets subscribed
  const auto topics = systemState();
  // Nothing in the manager's namespace that the nodelets' namespaces own.
  for (const char* stray : {"/camera/image", "/camera/loop_closure", "/camera/odom"}) {
    auto it = topics.find(stray);
    EXPECT_TRUE(it == topics.end() ||
                (it->second.publishers.empty() && it->second.subscribers.empty()))
        << stray << " is used: a name was resolved in the manager's namespace";
  }
  // Both nodelets (same manager process) take the remapped image, its
  // camera_info sibling and their namespace's odom.
  EXPECT_EQ(topics.count("/camera/image_raw") ? topics.at("/camera/image_raw").subscribers
                                              : std::set<std::string>(),
            std::set<std::string>{"/camera/camera_nodelet_manager"});
  EXPECT_TRUE(topics.count("/camera/camera_info"));
  EXPECT_TRUE(topics.count("/odom") && !topics.at("/odom").subscribers.empty());
  EXPECT_TRUE(topics.count("/robot/odom") && !topics.at("/robot/odom").subscribers.empty());

  ros::NodeHandle nh;
  StatusCounter root, robot;
  ros::Subscriber a = nh.subscribe("/bowg/keyframe_status", 10, &StatusCounter::on, &root);
  ros::Subscriber b = nh.subscribe("/robot/bowg/keyframe_status", 10, &StatusCounter::on, &robot);
  EXPECT_TRUE(imagesReachEveryNodelet("/camera/image_raw", {&root, &robot}, 60.0))
      << "keyframe statuses: /bowg " << root.get() << ", /robot/bowg " << robot.get();
}

TEST(LaunchFiles, OwnManagerUnderANamespaceResolvesRelativeTopicsThere) {
  // bowg.launch under ns="second" with image:=camera/image_raw.
  ASSERT_TRUE(waitForEnd("/second/camera/image_raw", false, 60.0));
  ASSERT_TRUE(waitForEnd("/second/loop_closure", true, 60.0));
  ros::NodeHandle nh;
  StatusCounter second;
  ros::Subscriber s = nh.subscribe("/second/bowg/keyframe_status", 10, &StatusCounter::on, &second);
  EXPECT_TRUE(imagesReachEveryNodelet("/second/camera/image_raw", {&second}, 60.0));
}

}  // namespace
}  // namespace bowg_ros
