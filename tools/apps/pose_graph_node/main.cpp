// bowg_pose_graph_node: the live pose-graph example (live_pose_graph.h).
#include <ros/ros.h>

#include <exception>

#include "live_pose_graph.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "bowg_pose_graph");
  ros::NodeHandle nh, pnh("~");
  try {
    bowg::pose_graph_node::LivePoseGraph graph(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("bowg_pose_graph_node: %s", e.what());
    return 1;
  }
  return 0;
}
